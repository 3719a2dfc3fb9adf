#include "lsdem/contact/ShearHistory.h"

#include <algorithm>
#include <stdexcept>

namespace lsdem {

namespace {

bool byNode(const ShearHistory::Entry& a, const ShearHistory::Entry& b)
{
    return a.node < b.node;
}

} // namespace

ShearHistory::ShearHistory(std::initializer_list<Entry> entries) : mEntries(entries)
{
    std::sort(mEntries.begin(), mEntries.end(), byNode);
    if (std::adjacent_find(mEntries.begin(), mEntries.end(), [](const Entry& a, const Entry& b) {
            return a.node == b.node;
        }) != mEntries.end())
        throw std::invalid_argument("ShearHistory: a node appears twice");
}

bool ShearHistory::contains(int node) const
{
    return std::binary_search(mEntries.begin(), mEntries.end(), Entry{node, Vec3::Zero()}, byNode);
}

Vec3 ShearHistory::force(int node) const
{
    const auto it =
        std::lower_bound(mEntries.begin(), mEntries.end(), Entry{node, Vec3::Zero()}, byNode);
    return it != mEntries.end() && it->node == node ? it->force : Vec3::Zero();
}

void ShearHistory::append(int node, const Vec3& force, double stiffness)
{
    if (!mEntries.empty() && node <= mEntries.back().node)
        throw std::invalid_argument("ShearHistory: nodes must be appended in increasing order");
    mEntries.push_back({node, force, stiffness});
}

void ShearHistory::replaceWith(std::vector<Entry>& next)
{
    mEntries.swap(next);
    next.clear();
}

} // namespace lsdem
