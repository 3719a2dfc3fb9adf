// Reading a scene from TOML. Every table goes through a TableReader that remembers which keys
// were asked for, so any key left over at the end is reported as unknown (a misspelt key must
// never be silently ignored). Messages name the file and line of the offending key.
#include "lsdem/scene/SceneFile.h"

#include "lsdem/scene/RandomRotation.h"
#include "lsdem/ls/Error.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

namespace lsdem {

namespace {

namespace fs = std::filesystem;

const double kPi = 3.14159265358979323846;

std::string joined(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
    return s;
}

std::string typeName(const toml::node& n)
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

// ---------------------------------------------------------------------------------------------
// Units: the declared system must be consistent (force = mass·length/time²), so that a density
// in mass/length³ and a stiffness in force/length³ combine without hidden factors.

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

// ---------------------------------------------------------------------------------------------

/// The tables of a [name.*] group (assets, materials) in the order they appear in the file.
std::vector<std::pair<std::string, const toml::table*>> tablesInFileOrder(
    const toml::table* group, const std::string& groupName, const std::string& path)
{
    std::vector<std::pair<std::string, const toml::table*>> out;
    if (!group) return out;
    for (auto&& [key, value] : *group) {
        const std::string name(key.str());
        if (!value.is_table()) {
            TableReader g(*group, "[" + groupName + "]", path);
            throw Error(g.at(value.source()),
                        groupName + "." + name + " must be a table, got " + typeName(value),
                        "write [" + groupName + "." + name + "] and its keys below it");
        }
        out.emplace_back(name, value.as_table());
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return a.second->source().begin.line < b.second->source().begin.line;
    });
    return out;
}

/// The array of tables `[[name]]`, or empty.
std::vector<const toml::table*> arrayOfTables(const toml::table& root, const std::string& name,
                                              const std::string& path)
{
    std::vector<const toml::table*> out;
    const toml::node* n = root.get(name);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) {
        throw Error(path + ":" + std::to_string(n->source().begin.line),
                    "'" + name + "' must be an array of tables",
                    "write each entry as [[" + name + "]] followed by its keys");
    }
    for (const toml::node& e : *a) out.push_back(e.as_table());
    return out;
}

std::string resolvePath(const std::string& directory, const std::string& file)
{
    fs::path p(file);
    if (p.is_relative()) p = fs::path(directory) / p;
    return fs::absolute(p).lexically_normal().string();
}

// ---------------------------------------------------------------------------------------------
// Assets

AssetSpec readAsset(const std::string& name, const toml::table& table, const Scene& scene)
{
    TableReader t(table, "[assets." + name + "]", scene.path);
    AssetSpec a;
    a.name = name;
    a.where = t.where();
    const int sources = int(t.has("file")) + int(t.has("mesh")) + int(t.has("shape"));
    if (sources != 1)
        t.fail("", sources == 0 ? "has no source" : "has more than one source",
               "give exactly one of file = \"grain.vdb\", mesh = \"grain.stl\" or "
               "shape = \"sphere\" | \"box\" | \"ellipsoid\"");
    auto existing = [&](const std::string& key) {
        const std::string p = resolvePath(scene.directory, t.string(key));
        if (!fs::is_regular_file(p))
            t.fail(key, "file not found: " + p,
                   "give a path relative to the scene's folder or an absolute one");
        return p;
    };
    if (t.has("file")) {
        a.file = existing("file");
        // A baked asset carries its own voxels and nodes; baking keys would be ignored.
        for (const char* key : {"voxel", "node_spacing", "nodes", "mesh_nodes", "areas"})
            if (t.has(key))
                t.fail(key, "has no effect on a baked asset (file = ...)",
                       "remove it, or bake again with lsdem-bake, or use mesh = ... instead");
        t.rejectUnknownKeys();
        return a;
    }
    if (t.has("mesh")) {
        a.meshFile = existing("mesh");
    } else {
        const std::string kind = t.choice("shape", {"sphere", "box", "ellipsoid"}, "");
        if (kind == "sphere") {
            if (t.has("size")) t.fail("size", "a sphere takes radius, not size", "write radius = R");
            a.shape = AnalyticShape::sphere(t.positive("radius"));
        } else {
            if (t.has("radius"))
                t.fail("radius", "a " + kind + " takes size, not radius",
                       kind == "box" ? "write size = [A, B, C] (full edge lengths)"
                                     : "write size = [a, b, c] (semi-axes)");
            const Vec3 s = t.vec3("size");
            if (!(s.minCoeff() > 0.0)) t.fail("size", "every size must be > 0", "");
            a.shape = kind == "box" ? AnalyticShape::box(s.x(), s.y(), s.z())
                                    : AnalyticShape::ellipsoid(s.x(), s.y(), s.z());
        }
    }
    BakeOptions& b = a.bake;
    b.voxelSize = t.positive("voxel");
    const int placements = int(t.has("node_spacing")) + int(t.has("nodes")) +
                           int(t.has("mesh_nodes") && t.boolean("mesh_nodes", false));
    if (placements != 1)
        t.fail("", placements == 0 ? "says nothing about its surface nodes"
                                   : "gives more than one way to place surface nodes",
               "give exactly one of node_spacing = SDP, nodes = N or mesh_nodes = true");
    std::ostringstream opts;
    opts << "scene " << scene.path << " asset " << name << ": voxel " << b.voxelSize;
    if (t.has("node_spacing")) {
        b.nodePlacement = NodePlacement::Spacing;
        b.nodeSpacing = t.positive("node_spacing");
        opts << " node_spacing " << b.nodeSpacing;
    } else if (t.has("nodes")) {
        b.nodePlacement = NodePlacement::Count;
        const long long n = t.positiveInteger("nodes");
        if (n > 100000000) t.fail("nodes", "is absurdly large", "give at most 1e8 nodes");
        b.nodeCount = static_cast<int>(n);
        opts << " nodes " << b.nodeCount;
    } else {
        if (a.shape) t.fail("mesh_nodes", "an analytic shape has no mesh vertices",
                            "use node_spacing or nodes");
        b.nodePlacement = NodePlacement::MeshVertices;
        opts << " mesh_nodes";
    }
    const std::string areas = t.choice("areas", {"mesh", "uniform"}, "mesh");
    b.areaRule = areas == "mesh" ? AreaRule::Mesh : AreaRule::Uniform;
    opts << " areas " << areas;
    b.optionsText = opts.str();
    t.rejectUnknownKeys();
    return a;
}

// ---------------------------------------------------------------------------------------------
// Names used across tables

template <typename Spec>
int indexByName(const std::vector<Spec>& specs, const std::string& name)
{
    for (size_t i = 0; i < specs.size(); ++i)
        if (specs[i].name == name) return static_cast<int>(i);
    return -1;
}

/// The index of the @a what (e.g. "material") that @a key names, or an error listing the names.
template <typename Spec>
int lookUp(TableReader& t, const std::string& key, const std::vector<Spec>& specs,
           const std::string& what, const std::string& howToDefine)
{
    const std::string name = t.string(key);
    const int i = indexByName(specs, name);
    if (i < 0) {
        std::vector<std::string> names;
        for (const Spec& s : specs) names.push_back("'" + s.name + "'");
        t.fail(key, "no " + what + " named '" + name + "'",
               (names.empty() ? "" : "use one of " + joined(names) + ", or ") + howToDefine);
    }
    return i;
}

int lookUpAsset(TableReader& t, const Scene& scene)
{
    return lookUp(t, "asset", scene.assets, "asset", "define it in an [assets.NAME] table");
}
int lookUpMaterial(TableReader& t, const Scene& scene)
{
    return lookUp(t, "material", scene.materials, "material",
                  "define it in a [materials.NAME] table");
}

// ---------------------------------------------------------------------------------------------
// Orientation: a quaternion [w, x, y, z] or an axis and an angle in degrees.

Quat readOrientation(TableReader& t)
{
    if (t.has("orientation") && t.has("axis_angle"))
        t.fail("axis_angle", "both orientation and axis_angle are given", "keep one of them");
    if (t.has("orientation")) {
        const std::vector<double> q = t.numbers("orientation", 4);
        Quat r(q[0], q[1], q[2], q[3]);
        if (!(r.norm() > 1e-12))
            t.fail("orientation", "is not a rotation (zero quaternion)",
                   "give a unit quaternion [w, x, y, z], e.g. [1, 0, 0, 0]");
        if (std::abs(r.norm() - 1.0) > 1e-6)
            t.fail("orientation", "is not a unit quaternion (norm " + TableReader::show(r.norm()) + ")",
                   "normalise it, or use axis_angle = [ax, ay, az, degrees]");
        return r.normalized();
    }
    if (t.has("axis_angle")) {
        const std::vector<double> v = t.numbers("axis_angle", 4);
        const Vec3 axis(v[0], v[1], v[2]);
        if (!(axis.norm() > 0.0))
            t.fail("axis_angle", "has a zero axis", "give a direction, e.g. [0, 0, 1, 30]");
        return Quat(Eigen::AngleAxisd(v[3] * kPi / 180.0, axis.normalized()));
    }
    return Quat::Identity();
}

/// The motion and velocities of a grain (or of every grain of a lattice).
void readMotion(TableReader& t, GrainSpec& g)
{
    const std::string motion = t.choice("motion", {"free", "fixed", "prescribed"}, "free");
    g.motion = motion == "free" ? GrainMotion::Free
             : motion == "fixed" ? GrainMotion::Fixed : GrainMotion::Prescribed;
    g.velocity = t.vec3("velocity", Vec3::Zero());
    g.angularVelocity = t.vec3("angular_velocity", Vec3::Zero());
    if (g.motion == GrainMotion::Fixed && (t.has("velocity") || t.has("angular_velocity")))
        t.fail(t.has("velocity") ? "velocity" : "angular_velocity",
               "a fixed grain cannot move",
               "remove the velocity, or write motion = \"prescribed\" to move it at that velocity");
    if (t.has("mass")) g.mass = t.positive("mass");
}

/// A uniform number in [0, 1) from the generator's raw 64-bit output: the standard library's
/// distributions are not specified bit for bit, so lattices would differ between compilers.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }


GrainSpec readGrain(TableReader& t, const Scene& scene)
{
    GrainSpec g;
    g.where = t.where();
    g.name = t.string("name", "");
    g.asset = lookUpAsset(t, scene);
    g.material = lookUpMaterial(t, scene);
    g.pose.position = t.vec3("position");
    g.pose.orientation = readOrientation(t);
    readMotion(t, g);
    t.rejectUnknownKeys();
    return g;
}

/// A block of count[0]×count[1]×count[2] grains at origin + (i, j, k)·spacing, optionally
/// jittered and randomly turned (seeded, reproducible everywhere).
void readLattice(TableReader& t, Scene& scene)
{
    GrainSpec model;
    model.where = t.where();
    const std::string prefix = t.string("name", "");
    model.asset = lookUpAsset(t, scene);
    model.material = lookUpMaterial(t, scene);
    const Vec3 origin = t.vec3("origin");
    const std::vector<double> c = t.numbers("count", 3);
    long long count[3];
    for (int d = 0; d < 3; ++d) {
        if (!(c[d] >= 1.0 && c[d] == std::floor(c[d]) && c[d] <= 1e6))
            t.fail("count", "must hold three positive integers", "write e.g. count = [3, 3, 3]");
        count[d] = static_cast<long long>(c[d]);
    }
    if (count[0] * count[1] * count[2] > 10000000)
        t.fail("count", "asks for more than 10 million grains", "use a smaller lattice");
    const Vec3 spacing = t.vec3("spacing");
    for (int d = 0; d < 3; ++d)
        if (count[d] > 1 && !(spacing[d] > 0.0))
            t.fail("spacing", "must be > 0 along every axis with more than one grain", "");
    const double jitter = t.nonNegative("jitter", 0.0);
    const bool randomOrientation = t.boolean("random_orientation", false);
    if (randomOrientation && (t.has("orientation") || t.has("axis_angle")))
        t.fail("random_orientation", "conflicts with a given orientation", "keep one of them");
    const Quat orientation = readOrientation(t);
    const long long seed = t.has("seed") ? t.integer("seed") : 1;
    readMotion(t, model);
    t.rejectUnknownKeys();

    std::mt19937_64 rng(static_cast<uint64_t>(seed));
    for (long long k = 0; k < count[2]; ++k)
        for (long long j = 0; j < count[1]; ++j)
            for (long long i = 0; i < count[0]; ++i) {
                GrainSpec g = model;
                if (!prefix.empty())
                    g.name = prefix + "_" + std::to_string(i) + "_" + std::to_string(j) + "_" +
                             std::to_string(k);
                g.pose.position = origin + Vec3(double(i) * spacing.x(), double(j) * spacing.y(),
                                                double(k) * spacing.z());
                if (jitter > 0.0)
                    for (int d = 0; d < 3; ++d)
                        g.pose.position[d] += jitter * (2.0 * uniform01(rng) - 1.0);
                g.pose.orientation = randomOrientation ? randomRotation([&] { return uniform01(rng); })
                                                       : orientation;
                scene.grains.push_back(g);
            }
}

// ---------------------------------------------------------------------------------------------

ContactSpec readContact(TableReader& t, const Scene& scene)
{
    ContactSpec c;
    c.where = t.where();
    const toml::node& m = t.node("materials");
    const toml::array* pair = m.as_array();
    if (!pair || pair->size() != 2 || !(*pair)[0].is_string() || !(*pair)[1].is_string())
        t.fail("materials", "expected two material names", "write materials = [\"steel\", \"wall\"]");
    int idx[2];
    for (int s = 0; s < 2; ++s) {
        const std::string name = (*pair)[static_cast<size_t>(s)].as_string()->get();
        idx[s] = indexByName(scene.materials, name);
        if (idx[s] < 0)
            t.fail("materials", "no material named '" + name + "'", "define [materials." + name + "]");
    }
    c.materialA = idx[0];
    c.materialB = idx[1];
    ContactModel& model = c.model;
    model.formulation = parseFormulation(
        t.choice("formulation", {"original", "adapted", "single-node", "volume"}, "adapted"));
    model.testing = parseNodeTesting(
        t.choice("testing", {"one-way", "symmetric"}, nodeTestingName(model.testing)));
    model.normalStiffness = t.positive("normal_stiffness");
    model.shearStiffness = t.nonNegative("shear_stiffness", 0.0);
    model.friction = t.nonNegative("friction", 0.0);
    if (model.shearStiffness > 0.0 && (model.formulation == Formulation::SingleNode ||
                                       model.formulation == Formulation::Volume))
        t.fail("shear_stiffness", "has no effect with formulation " +
                                      formulationName(model.formulation),
               "use original or adapted for tangential forces, or remove it");
    c.restitution = t.number("restitution", 1.0);
    if (!(c.restitution > 0.0 && c.restitution <= 1.0))
        t.fail("restitution", "must be in (0, 1] (got " + TableReader::show(c.restitution) + ")",
               "1 means no contact damping");
    t.rejectUnknownKeys();
    return c;
}

/// A boundary's name becomes part of a file name (boundary_<name>.csv).
bool isFileNameSafe(const std::string& s)
{
    if (s.empty()) return false;
    for (char ch : s)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
}

BoundarySpec readBoundary(TableReader& t, const Scene& scene)
{
    BoundarySpec b;
    b.where = t.where();
    b.name = t.string("name");
    if (!isFileNameSafe(b.name))
        t.fail("name", "'" + b.name + "' cannot name a file (boundary_<name>.csv)",
               "use letters, digits, '_' and '-' only");
    const std::string type = t.choice("type", {"plane", "sphere", "level-set"}, "");
    if (type.empty()) t.fail("", "missing key 'type'", "add type = \"plane\" | \"sphere\" | \"level-set\"");
    b.material = lookUpMaterial(t, scene);
    b.velocity = t.vec3("velocity", Vec3::Zero());
    if (type == "plane") {
        b.shape = BoundaryShape::Plane;
        b.point = t.vec3("point");
        b.normal = t.unitVec3("normal");
        if (t.has("extent")) {
            const std::vector<double> e = t.numbers("extent", 2);
            if (!(e[0] > 0.0 && e[1] > 0.0))
                t.fail("extent", "both widths must be > 0", "omit extent for an unbounded plane");
            b.extentU = e[0];
            b.extentV = e[1];
            b.axisU = t.has("axis_u") ? t.unitVec3("axis_u") : b.normal.unitOrthogonal();
            // Keep only the in-plane part, so a slightly off axis still defines the patch.
            const Vec3 inPlane = b.axisU - b.axisU.dot(b.normal) * b.normal;
            if (inPlane.norm() < 1e-6)
                t.fail("axis_u", "is parallel to the normal", "give a direction within the plane");
            b.axisU = inPlane.normalized();
        } else if (t.has("axis_u")) {
            t.fail("axis_u", "only makes sense with extent", "add extent = [wu, wv] or remove it");
        }
        b.thickness = t.has("thickness") ? t.positive("thickness") : 0.0;
    } else if (type == "sphere") {
        b.shape = BoundaryShape::Sphere;
        b.center = t.vec3("center");
        b.radius = t.positive("radius");
    } else {
        b.shape = BoundaryShape::LevelSet;
        b.asset = lookUpAsset(t, scene);
        b.pose.position = t.vec3("position");
        b.pose.orientation = readOrientation(t);
    }
    t.rejectUnknownKeys();
    return b;
}

void readSimulation(const toml::table* table, Scene& scene)
{
    if (!table)
        throw Error(scene.path, "missing [simulation]",
                    "add [simulation] with at least an end condition (end_time, end_steps or "
                    "end_displacement)");
    TableReader t(*table, "[simulation]", scene.path);
    scene.gravity = t.vec3("gravity", Vec3::Zero());
    scene.globalDamping = t.number("global_damping", 0.0);
    if (!(scene.globalDamping >= 0.0 && scene.globalDamping < 1.0))
        t.fail("global_damping", "must be in [0, 1)", "0 means none; 0.1–0.3 settles grains");
    if (t.has("time_step")) {
        const toml::node& n = t.node("time_step");
        if (n.is_string()) {
            if (n.as_string()->get() != "auto")
                t.fail("time_step", "unknown value '" + n.as_string()->get() + "'",
                       "write time_step = \"auto\" or a positive number");
        } else {
            scene.timeStep.fixed = t.positive("time_step");
        }
    }
    if (t.has("safety")) {
        if (scene.timeStep.fixed > 0.0)
            t.fail("safety", "only applies to time_step = \"auto\"", "remove it");
        scene.timeStep.safety = t.positive("safety");
        if (scene.timeStep.safety > 1.0)
            t.fail("safety", "must be in (0, 1]", "0.1–0.3 is usual");
    }
    EndCondition& end = scene.end;
    if (t.has("end_time")) end.time = t.positive("end_time");
    if (t.has("end_steps")) end.steps = t.positiveInteger("end_steps");
    if (t.has("end_displacement")) {
        const toml::node& n = t.node("end_displacement");
        if (!n.is_table())
            t.fail("end_displacement", "expected a table", "write end_displacement = { boundary = \"top\", value = 0.3 }");
        TableReader e(*n.as_table(), "[simulation] end_displacement", scene.path);
        end.boundary = lookUp(e, "boundary", scene.boundaries, "boundary",
                              "name a [[boundaries]] entry");
        end.displacement = e.positive("value");
        e.rejectUnknownKeys();
        if (!(scene.boundaries[static_cast<size_t>(end.boundary)].velocity.norm() > 0.0))
            e.fail("boundary", "'" + scene.boundaries[static_cast<size_t>(end.boundary)].name +
                                   "' does not move, so it never reaches the displacement",
                   "give that boundary a velocity, or end by end_time / end_steps");
    }
    if (end.time <= 0.0 && end.steps <= 0 && end.boundary < 0)
        t.fail("", "has no end condition", "add end_time, end_steps or end_displacement");
    t.rejectUnknownKeys();
}

void readOutput(const toml::table* table, Scene& scene)
{
    if (!table) return;
    TableReader t(*table, "[output]", scene.path);
    OutputSpec& o = scene.output;
    if (t.has("history_every") && t.has("history_period"))
        t.fail("history_period", "both history_every and history_period are given", "keep one");
    if (t.has("history_every")) o.historyEvery = t.positiveInteger("history_every");
    if (t.has("history_period")) o.historyPeriod = t.positive("history_period");
    o.vtkPeriod = t.nonNegative("vtk_period", 0.0);
    o.checkpointPeriod = t.nonNegative("checkpoint_period", 0.0);
    o.contactForces = t.boolean("contact_forces", true);
    t.rejectUnknownKeys();
}

/// Every pair of materials that can meet needs a [[contacts]] entry, and only one.
void checkContactPairs(const Scene& scene)
{
    const size_t m = scene.materials.size();
    std::vector<const ContactSpec*> table(m * m, nullptr);
    for (const ContactSpec& c : scene.contacts) {
        const size_t ab = static_cast<size_t>(c.materialA) * m + static_cast<size_t>(c.materialB);
        const size_t ba = static_cast<size_t>(c.materialB) * m + static_cast<size_t>(c.materialA);
        if (table[ab])
            throw Error(c.where,
                        "[[contacts]]: a second entry for materials '" +
                            scene.materials[static_cast<size_t>(c.materialA)].name + "' and '" +
                            scene.materials[static_cast<size_t>(c.materialB)].name + "'",
                        "the first is at " + table[ab]->where + "; keep one");
        table[ab] = table[ba] = &c;
    }
    std::vector<int> grainsOf(m, 0);
    for (const GrainSpec& g : scene.grains) ++grainsOf[static_cast<size_t>(g.material)];
    auto require = [&](int a, int b, const std::string& where) {
        if (table[static_cast<size_t>(a) * m + static_cast<size_t>(b)]) return;
        const std::string na = scene.materials[static_cast<size_t>(a)].name;
        const std::string nb = scene.materials[static_cast<size_t>(b)].name;
        throw Error(where, "no contact law between materials '" + na + "' and '" + nb + "'",
                    "add [[contacts]] with materials = [\"" + na + "\", \"" + nb +
                        "\"] and its normal_stiffness");
    };
    for (const GrainSpec& g : scene.grains) {
        for (size_t other = 0; other < m; ++other) {
            const bool meets = static_cast<int>(other) == g.material ? grainsOf[other] >= 2
                                                                     : grainsOf[other] >= 1;
            if (meets) require(g.material, static_cast<int>(other), g.where);
        }
        for (const BoundarySpec& b : scene.boundaries) require(g.material, b.material, b.where);
    }
}

void checkUniqueNames(const Scene& scene)
{
    std::map<std::string, const std::string*> seen;
    for (const GrainSpec& g : scene.grains) {
        if (g.name.empty()) continue;
        const auto [it, fresh] = seen.emplace(g.name, &g.where);
        if (!fresh)
            throw Error(g.where, "a second grain named '" + g.name + "'",
                        "the first is at " + *it->second + "; give grains distinct names");
    }
    seen.clear();
    for (const BoundarySpec& b : scene.boundaries) {
        const auto [it, fresh] = seen.emplace(b.name, &b.where);
        if (!fresh)
            throw Error(b.where, "a second boundary named '" + b.name + "'",
                        "the first is at " + *it->second + "; give boundaries distinct names");
    }
}

} // namespace

Scene parseScene(const std::string& text, const std::string& path)
{
    Scene scene;
    scene.path = path;
    scene.directory = fs::absolute(fs::path(path)).parent_path().string();
    scene.text = text;

    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw Error(path + ":" + std::to_string(e.source().begin.line),
                    "not valid TOML: " + std::string(e.description()),
                    "see docs/scenes.md and the examples in assets/scenes/");
    }

    const std::vector<std::string> sections = {"units",     "assets",     "materials",
                                               "contacts",  "grains",     "lattices",
                                               "boundaries", "simulation", "output"};
    for (auto&& [key, value] : root) {
        const std::string k(key.str());
        if (std::find(sections.begin(), sections.end(), k) == sections.end())
            throw Error(path + ":" + std::to_string(value.source().begin.line),
                        "unknown top-level key or table '" + k + "'",
                        "use one of: " + joined(sections));
    }
    for (const char* single : {"units", "assets", "materials", "simulation", "output"}) {
        const toml::node* n = root.get(single);
        if (n && !n->is_table())
            throw Error(path + ":" + std::to_string(n->source().begin.line),
                        "'" + std::string(single) + "' must be a table",
                        "write [" + std::string(single) + "] (or [" + single +
                            ".name]) followed by its keys");
    }

    scene.units = readUnits(root["units"].as_table(), path);
    for (const auto& [name, table] : tablesInFileOrder(root["assets"].as_table(), "assets", path))
        scene.assets.push_back(readAsset(name, *table, scene));
    for (const auto& [name, table] :
         tablesInFileOrder(root["materials"].as_table(), "materials", path)) {
        TableReader t(*table, "[materials." + name + "]", path);
        MaterialSpec m;
        m.name = name;
        m.density = t.nonNegative("density", 0.0);
        t.rejectUnknownKeys();
        scene.materials.push_back(m);
    }
    if (scene.materials.empty())
        throw Error(path, "no materials", "add e.g. [materials.steel] with density = 7.85e-9");

    int n = 0;
    for (const toml::table* t : arrayOfTables(root, "contacts", path)) {
        TableReader r(*t, "[[contacts]] #" + std::to_string(++n), path);
        scene.contacts.push_back(readContact(r, scene));
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "grains", path)) {
        TableReader r(*t, "[[grains]] #" + std::to_string(++n), path);
        scene.grains.push_back(readGrain(r, scene));
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "lattices", path)) {
        TableReader r(*t, "[[lattices]] #" + std::to_string(++n), path);
        readLattice(r, scene);
    }
    if (scene.grains.empty())
        throw Error(path, "no grains", "add [[grains]] or [[lattices]] entries");
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "boundaries", path)) {
        TableReader r(*t, "[[boundaries]] #" + std::to_string(++n), path);
        scene.boundaries.push_back(readBoundary(r, scene));
    }
    readSimulation(root["simulation"].as_table(), scene);
    readOutput(root["output"].as_table(), scene);
    checkUniqueNames(scene);
    checkContactPairs(scene);
    return scene;
}

Scene readSceneFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in || fs::is_directory(path))
        throw Error(path, "cannot read the scene file", "check the path and its permissions");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path);
}

} // namespace lsdem
