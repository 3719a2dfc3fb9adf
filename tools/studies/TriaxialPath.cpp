#include "studies/TriaxialPath.h"

#include <utility>

namespace lsdem {

namespace {

const std::vector<std::pair<TriaxialPath, const char*>>& names()
{
    static const std::vector<std::pair<TriaxialPath, const char*>> list = {
        {TriaxialPath::Compression, "compression"},   {TriaxialPath::Extension, "extension"},
        {TriaxialPath::ConstantP, "constant-p"},      {TriaxialPath::TrueTriaxial, "true-triaxial"},
        {TriaxialPath::Undrained, "undrained"},       {TriaxialPath::UnloadReload, "unload-reload"},
        {TriaxialPath::Cyclic, "cyclic"}};
    return list;
}

} // namespace

std::string triaxialPathName(TriaxialPath path)
{
    for (const auto& [p, name] : names())
        if (p == path) return name;
    return "?";
}

std::optional<TriaxialPath> triaxialPathNamed(const std::string& name)
{
    for (const auto& [p, n] : names())
        if (name == n) return p;
    return std::nullopt;
}

const std::vector<TriaxialPath>& allTriaxialPaths()
{
    static const std::vector<TriaxialPath> all = [] {
        std::vector<TriaxialPath> v;
        for (const auto& [p, name] : names()) v.push_back(p);
        return v;
    }();
    return all;
}

} // namespace lsdem
