/// @file TableReader.h
/// @brief Reading one TOML table of a scene (private to the scene reader): typed getters that
///        check types and ranges, and a final check that no key was left unread, so a misspelt
///        key is never silently ignored. Messages name the file and line of the offending key.
#pragma once

#include "lsdem/core/Error.h"
#include "lsdem/core/Vec3.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace lsdem::scenefile {

inline std::string joined(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
    return s;
}

inline std::string typeName(const toml::node& n)
{
    switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
    }
}

/// One TOML table being read: typed getters that check ranges, and a final check that no key
/// was left unread. @a label says which table it is in messages ("[output]", "[[grains]] #2").
class TableReader
{
public:
    TableReader(const toml::table& table, std::string label, const std::string& path)
        : mTable(table), mLabel(std::move(label)), mPath(path)
    {
    }

    const std::string& label() const { return mLabel; }

    /// "scene.toml:12" for the key, or for the table itself if the key is absent.
    std::string where(const std::string& key = "") const
    {
        const toml::node* n = key.empty() ? nullptr : mTable.get(key);
        return at(n ? n->source() : mTable.source());
    }
    std::string at(const toml::source_region& s) const
    {
        return s.begin.line > 0 ? mPath + ":" + std::to_string(s.begin.line) : mPath;
    }

    [[noreturn]] void fail(const std::string& key, const std::string& problem,
                           const std::string& fix) const
    {
        throw Error(where(key), mLabel + (key.empty() ? "" : " " + key) + ": " + problem, fix);
    }

    bool has(const std::string& key)
    {
        mRead.insert(key);
        return mTable.contains(key);
    }

    const toml::node& node(const std::string& key)
    {
        mRead.insert(key);
        const toml::node* n = mTable.get(key);
        if (!n) fail("", "missing key '" + key + "'", "add " + key + " = ...");
        return *n;
    }

    double number(const std::string& key, const std::string& hint = "a number")
    {
        const toml::node& n = node(key);
        double v = 0.0;
        if (n.is_integer())
            v = static_cast<double>(n.as_integer()->get());
        else if (n.is_floating_point())
            v = n.as_floating_point()->get();
        else
            fail(key, "expected " + hint + ", got " + typeName(n), "write e.g. " + key + " = 1.0");
        if (!std::isfinite(v)) fail(key, "is not finite", "give a finite number");
        return v;
    }
    double number(const std::string& key, double fallback)
    {
        return has(key) ? number(key) : fallback;
    }
    double positive(const std::string& key)
    {
        const double v = number(key, std::string("a positive number"));
        if (!(v > 0.0)) fail(key, "must be > 0 (got " + show(v) + ")", "give a positive value");
        return v;
    }
    double nonNegative(const std::string& key, double fallback)
    {
        if (!has(key)) return fallback;
        const double v = number(key);
        if (v < 0.0) fail(key, "must be >= 0 (got " + show(v) + ")", "give a value >= 0");
        return v;
    }
    long long integer(const std::string& key)
    {
        const toml::node& n = node(key);
        if (!n.is_integer())
            fail(key, "expected an integer, got " + typeName(n), "write e.g. " + key + " = 10");
        return n.as_integer()->get();
    }
    long long positiveInteger(const std::string& key)
    {
        const long long v = integer(key);
        if (v <= 0) fail(key, "must be a positive integer (got " + std::to_string(v) + ")", "");
        return v;
    }
    std::string string(const std::string& key)
    {
        const toml::node& n = node(key);
        if (!n.is_string())
            fail(key, "expected a string, got " + typeName(n), "write " + key + " = \"...\"");
        return n.as_string()->get();
    }
    std::string string(const std::string& key, const std::string& fallback)
    {
        return has(key) ? string(key) : fallback;
    }
    bool boolean(const std::string& key, bool fallback)
    {
        if (!has(key)) return fallback;
        const toml::node& n = node(key);
        if (!n.is_boolean())
            fail(key, "expected true or false, got " + typeName(n), "write " + key + " = true");
        return n.as_boolean()->get();
    }
    std::vector<double> numbers(const std::string& key, size_t count)
    {
        const toml::node& n = node(key);
        const toml::array* a = n.as_array();
        const std::string want = "an array of " + std::to_string(count) + " numbers";
        if (!a || a->size() != count)
            fail(key, "expected " + want + ", got " +
                          (a ? "an array of " + std::to_string(a->size()) : typeName(n)),
                 "write e.g. " + key + " = [" + (count == 2 ? "1, 1" : count == 3 ? "0, 0, 0" : "1, 0, 0, 0") + "]");
        std::vector<double> v;
        for (const toml::node& e : *a) {
            if (e.is_integer())
                v.push_back(static_cast<double>(e.as_integer()->get()));
            else if (e.is_floating_point())
                v.push_back(e.as_floating_point()->get());
            else
                fail(key, "expected " + want + ", found " + typeName(e) + " in it", "");
            if (!std::isfinite(v.back())) fail(key, "holds a value that is not finite", "");
        }
        return v;
    }
    Vec3 vec3(const std::string& key)
    {
        const std::vector<double> v = numbers(key, 3);
        return Vec3(v[0], v[1], v[2]);
    }
    Vec3 vec3(const std::string& key, const Vec3& fallback)
    {
        return has(key) ? vec3(key) : fallback;
    }
    Vec3 unitVec3(const std::string& key)
    {
        const Vec3 v = vec3(key);
        if (!(v.norm() > 0.0)) fail(key, "must not be the zero vector", "give a direction");
        return v.normalized();
    }
    /// One of @a choices, by name.
    std::string choice(const std::string& key, const std::vector<std::string>& choices,
                       const std::string& fallback)
    {
        if (!has(key)) return fallback;
        const std::string v = string(key);
        if (std::find(choices.begin(), choices.end(), v) == choices.end())
            fail(key, "unknown value '" + v + "'", "use one of: " + joined(choices));
        return v;
    }

    /// Every key of the table must have been read: anything else is a typo or a misplaced key.
    void rejectUnknownKeys() const
    {
        for (auto&& [key, value] : mTable) {
            const std::string k(key.str());
            if (mRead.count(k)) continue;
            std::vector<std::string> known(mRead.begin(), mRead.end());
            throw Error(at(value.source()), mLabel + ": unknown key '" + k + "'",
                        "remove it or use one of: " + joined(known));
        }
    }

    static std::string show(double v)
    {
        std::ostringstream s;
        s << v;
        return s.str();
    }

private:
    const toml::table& mTable;
    std::string mLabel;
    const std::string& mPath;
    std::set<std::string> mRead;
};

} // namespace lsdem::scenefile
