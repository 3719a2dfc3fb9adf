// [units]: the declared unit system must be consistent (force = mass·length/time²), so that a
// density in mass/length³ and a stiffness in force/length³ combine without hidden factors.
#include "SceneSections.h"

#include <map>

namespace lsdem::scenefile {

namespace {

double unitScale(TableReader& t, const std::string& key, const std::string& fallback,
                 const std::map<std::string, double>& toSI)
{
    const std::string name = t.string(key, fallback);
    const auto it = toSI.find(name);
    if (it == toSI.end()) {
        std::vector<std::string> names;
        for (const auto& [n, s] : toSI) names.push_back(n);
        t.fail(key, "unknown unit '" + name + "'", "use one of: " + joined(names));
    }
    return it->second;
}

} // namespace

UnitSystem readUnits(const toml::table* table, const std::string& path)
{
    UnitSystem u;
    if (!table) return u;  // mm, tonne, s, N
    TableReader t(*table, "[units]", path);
    const double length = unitScale(t, "length", u.length,
                                    {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}});
    const double mass = unitScale(t, "mass", u.mass, {{"kg", 1.0}, {"g", 1e-3}, {"tonne", 1e3}});
    const double time = unitScale(t, "time", u.time, {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}});
    const std::map<std::string, double> forces = {
        {"N", 1.0}, {"kN", 1e3}, {"mN", 1e-3}, {"MN", 1e6}, {"uN", 1e-6}};
    const double force = unitScale(t, "force", u.force, forces);
    u.length = t.string("length", u.length);
    u.mass = t.string("mass", u.mass);
    u.time = t.string("time", u.time);
    u.force = t.string("force", u.force);
    t.rejectUnknownKeys();
    const double implied = mass * length / (time * time);
    if (std::abs(force - implied) > 1e-9 * implied) {
        std::string consistent;
        for (const auto& [name, scale] : forces)
            if (std::abs(scale - implied) <= 1e-9 * implied) consistent = name;
        throw Error(t.where("force"),
                    "[units] are inconsistent: 1 " + u.mass + "·" + u.length + "/" + u.time +
                        "² is not 1 " + u.force,
                    consistent.empty()
                        ? "choose units with force = mass·length/time², e.g. mm, tonne, s, N"
                        : "use force = \"" + consistent + "\" with these units");
    }
    return u;
}

} // namespace lsdem::scenefile
