// Writing a scene as TOML, section by section in the reader's order, so that the file reads
// back to the same scene. Strings (and keys that are not bare) are escaped by toml++; numbers
// are written by std::to_chars in their shortest form that reads back to the same double
// (Debian's toml++ 3.3 library prints 17 significant digits, 0.1 as 0.10000000000000001).
#include "lsdem/scene/SceneWriter.h"

#include "lsdem/scene/BoundaryKeys.h"
#include "lsdem/scene/GrainKeys.h"
#include "lsdem/scene/SceneSettings.h"
#include "lsdem/scene/SceneValidation.h"

#include "lsdem/contact/ContactCoefficients.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <toml++/toml.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

namespace lsdem {

namespace {

namespace fs = std::filesystem;

/// A TOML document written line by line.
class TomlText
{
public:
    void comment(const std::string& text)
    {
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);)
            mOut << (line.empty() ? "#" : "# " + line) << "\n";
    }
    void table(const std::string& header) { blank(), mOut << "[" << header << "]\n"; }
    void arrayTable(const std::string& name) { blank(), mOut << "[[" << name << "]]\n"; }

    void string(const std::string& key, const std::string& value)
    {
        mOut << key << " = " << quoted(value) << "\n";
    }
    void number(const std::string& key, double value, const std::string& note = "")
    {
        mOut << key << " = " << numberText(value, key) << (note.empty() ? "" : "   # " + note)
             << "\n";
    }
    void integer(const std::string& key, long long value) { mOut << key << " = " << value << "\n"; }
    void boolean(const std::string& key, bool value)
    {
        mOut << key << " = " << (value ? "true" : "false") << "\n";
    }
    void numbers(const std::string& key, std::initializer_list<double> values)
    {
        mOut << key << " = [";
        const char* separator = "";
        for (double v : values) mOut << separator << numberText(v, key), separator = ", ";
        mOut << "]\n";
    }
    void vec3(const std::string& key, const Vec3& v) { numbers(key, {v.x(), v.y(), v.z()}); }
    void strings(const std::string& key, const std::string& a, const std::string& b)
    {
        strings(key, {a, b});
    }
    void strings(const std::string& key, const std::vector<std::string>& values)
    {
        mOut << key << " = [";
        const char* separator = "";
        for (const std::string& v : values) mOut << separator << quoted(v), separator = ", ";
        mOut << "]\n";
    }
    /// key = { name = "...", value = ... } (the end displacement).
    void inlineTable(const std::string& key, const std::string& nameKey, const std::string& name,
                     const std::string& valueKey, double value)
    {
        mOut << key << " = { " << nameKey << " = " << quoted(name) << ", " << valueKey << " = "
             << numberText(value, key) << " }\n";
    }

    /// A key as TOML wants it: bare if it can be, else a quoted string.
    static std::string key(const std::string& k)
    {
        bool bare = !k.empty();
        for (char c : k)
            bare = bare && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
        return bare ? k : quoted(k);
    }

    std::string str() const { return mOut.str(); }

private:
    void blank()
    {
        if (mOut.tellp() > 0) mOut << "\n";
    }
    static std::string quoted(const std::string& s)
    {
        std::ostringstream out;
        out << toml::value<std::string>(s);
        return out.str();
    }
    static std::string numberText(double v, const std::string& key)
    {
        if (!std::isfinite(v))
            throw Error("", "cannot write " + key + " = " + lsdem::numberText(v) + " to a scene file",
                        "every number in a scene must be finite");
        char buffer[64];
        const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
        std::string text(buffer, end);
        // TOML tells floats from integers by a point or an exponent.
        if (text.find_first_of(".eE") == std::string::npos) text += ".0";
        return text;
    }

    std::ostringstream mOut;
};

/// @a file relative to @a directory if it lies below it, else absolute.
std::string pathFrom(const std::string& directory, const std::string& file)
{
    const fs::path absolute = fs::absolute(file).lexically_normal();
    const fs::path relative =
        absolute.lexically_relative(fs::absolute(directory).lexically_normal());
    if (relative.empty() || *relative.begin() == "..") return absolute.string();
    return relative.string();
}


void writeBakeKeys(TomlText& t, const BakeOptions& b, bool forMesh)
{
    t.number("voxel", b.voxelSize);
    switch (b.nodePlacement) {
    case NodePlacement::Spacing: t.number("node_spacing", b.nodeSpacing); break;
    case NodePlacement::Count: t.integer("nodes", b.nodeCount); break;
    case NodePlacement::MeshVertices: t.boolean("mesh_nodes", true); break;
    }
    t.string("areas", b.areaRule == AreaRule::Mesh ? "mesh" : "uniform");
    // (For a mesh's nodes only: the reader refuses it for a shape or with mesh_nodes.)
    if (b.nodeLayout != NodeLayout::Automatic && b.nodePlacement != NodePlacement::MeshVertices &&
        forMesh)
        t.string("node_layout", nodeLayoutName(b.nodeLayout));
}

void writeAsset(TomlText& t, const AssetSpec& a, const std::string& directory)
{
    t.table("assets." + TomlText::key(a.name));
    if (!a.file.empty()) {
        t.string("file", pathFrom(directory, a.file));
        return;
    }
    if (a.loaded)
        throw Error(a.where, "asset '" + a.name + "' is held only in memory",
                    "save it (saveAsset) and set its file before writing the scene");
    if (!a.meshFile.empty()) {
        t.string("mesh", pathFrom(directory, a.meshFile));
    } else if (a.shape) {
        const AnalyticShape& s = *a.shape;
        switch (s.kind) {
        case AnalyticShape::Kind::Sphere:
            t.string("shape", "sphere");
            t.number("radius", s.size.x());
            break;
        case AnalyticShape::Kind::Box:
            t.string("shape", "box");
            t.vec3("size", s.size);
            break;
        case AnalyticShape::Kind::Ellipsoid:
            t.string("shape", "ellipsoid");
            t.vec3("size", s.size);
            break;
        }
    } else {
        throw Error(a.where, "asset '" + a.name + "' has no source",
                    "give it a file, a mesh or a shape");
    }
    writeBakeKeys(t, a.bake, !a.meshFile.empty());
}

void writeContact(TomlText& t, const Scene& scene, const ContactSpec& c)
{
    const ContactModel& m = c.model;
    t.arrayTable("contacts");
    t.strings("materials", scene.materials[c.materialA].name, scene.materials[c.materialB].name);
    // The contact library's schema (ContactCoefficients.h): its words, then its numbers, each
    // what is required or not at its default, a number with its unit where the formulation
    // decides it.
    for (const ContactChoice& k : contactChoices())
        if (k.written(m)) t.string(k.key, k.get(m));
    for (const ContactCoefficient& k : contactCoefficients())
        if (k.written(m)) t.number(k.key, k.get(m), k.unit ? k.unit(m) : "");
}

void writeOrientation(TomlText& t, const Quat& q)
{
    t.numbers("orientation", {q.w(), q.x(), q.y(), q.z()});
}

/// A grain by its keys (GrainKeys.h), so the writer gives what the reader reads back.
void writeGrain(TomlText& t, const Scene& scene, const GrainSpec& g)
{
    const GrainKeys k = grainKeysOf(g);
    t.arrayTable("grains");
    if (!k.name.empty()) t.string("name", k.name);
    t.string("asset", scene.assets[size_t(k.asset)].name);
    t.string("material", scene.materials[size_t(k.material)].name);
    t.vec3("position", *k.position);
    writeOrientation(t, *k.orientation);
    if (k.motion) t.string("motion", *k.motion);
    if (k.velocity) t.vec3("velocity", *k.velocity);
    if (k.angularVelocity) t.vec3("angular_velocity", *k.angularVelocity);
    if (k.mass) t.number("mass", *k.mass);
}

/// A boundary by its keys (BoundaryKeys.h), so the writer gives what the reader reads back.
void writeBoundary(TomlText& t, const Scene& scene, const BoundarySpec& b)
{
    const BoundaryKeys k = boundaryKeysOf(b, scene);
    const auto vector = [&t](const char* key, const std::optional<Vec3>& v) {
        if (v) t.vec3(key, *v);
    };
    const auto number = [&t](const char* key, const std::optional<double>& v) {
        if (v) t.number(key, *v);
    };
    t.arrayTable("boundaries");
    t.string("name", k.name);
    t.string("type", k.type);
    if (k.asset) t.string("asset", scene.assets[size_t(*k.asset)].name);
    t.string("material", scene.materials[size_t(k.material)].name);
    vector("point", k.point);
    vector("normal", k.normal);
    if (k.extent) t.numbers("extent", {(*k.extent)[0], (*k.extent)[1]});
    vector("axis_u", k.axisU);
    vector("center", k.center);
    vector("axis", k.axis);
    number("radius", k.radius);
    number("thickness", k.thickness);
    vector("position", k.position);
    if (k.orientation) writeOrientation(t, *k.orientation);
    number("stress", k.servo.stress);
    if (k.servo.areaWalls) t.strings("area_walls", *k.servo.areaWalls);
    number("area", k.servo.area);
    number("max_speed", k.servo.maxSpeed);
    number("servo_gain", k.servo.gain);
    vector("velocity", k.velocity);
}

void writeMembrane(TomlText& t, const Scene& scene, const MembraneSpec& m,
                   const std::string& directory)
{
    t.arrayTable("membranes");
    t.string("name", m.name);
    t.string("material", scene.materials[size_t(m.material)].name);
    t.string("shape", "tube");
    t.number("youngs", m.rubber.youngs);
    t.number("poisson", m.rubber.poisson);
    t.number("thickness", m.rubber.thickness);
    t.number("density", m.rubber.density);
    t.number("pressure", m.pressure);
    t.number("drag", m.drag);
    t.vec3("base", m.base);
    t.vec3("axis", m.axis);
    t.number("radius", m.radius);
    t.number("height", m.height);
    t.integer("segments", m.segments);
    t.integer("rings", m.rings);
    t.number("prestretch", m.prestretch);
    if (!m.hold.empty()) {
        std::vector<std::string> names;
        for (int b : m.hold) names.push_back(scene.boundaries[size_t(b)].name);
        t.strings("hold", names);
    }
    if (!m.state.empty()) t.string("state", pathFrom(directory, m.state));
}

/// The settings of @a section (SceneSettings.h) in the schema's order, those that the file
/// must give; @a special writes the ones with a form of their own in a file.
template <class Special>
void writeSettings(TomlText& t, const Scene& scene, const std::string& section, Special special)
{
    for (const SceneSetting& s : sceneSettings()) {
        if (s.section != section) continue;
        if (s.form == SettingForm::OwnForm) {
            special(s.key);
            continue;
        }
        if (!s.written(scene)) continue;
        const SettingValue v = s.get(scene);
        if (const double* d = std::get_if<double>(&v)) t.number(s.key, *d);
        if (const long long* n = std::get_if<long long>(&v)) t.integer(s.key, *n);
        if (const bool* b = std::get_if<bool>(&v)) t.boolean(s.key, *b);
        if (const Vec3* x = std::get_if<Vec3>(&v)) t.vec3(s.key, *x);
    }
}

void writeSimulation(TomlText& t, const Scene& scene)
{
    t.table("simulation");
    // time_step: a number, or "auto" with its safety.
    writeSettings(t, scene, "simulation", [&](const std::string& key) {
        if (key != "time_step") return;
        if (scene.timeStep.fixed > 0.0) {
            t.number("time_step", scene.timeStep.fixed);
        } else {
            t.string("time_step", "auto");
            t.number("safety", scene.timeStep.safety);
        }
    });
    const EndCondition& end = scene.end;
    if (end.boundary >= 0)
        t.inlineTable("end_displacement", "boundary", scene.boundaries[end.boundary].name,
                      "value", end.displacement);
}

void writeOutput(TomlText& t, const Scene& scene)
{
    t.table("output");
    writeSettings(t, scene, "output", [](const std::string&) {});
}

} // namespace

std::string sceneToToml(const Scene& scene, const std::string& sceneDirectory,
                        const std::string& header)
{
    // What is written holds to the rules a file is read by. (A scene still being built, without
    // grains or an end condition yet, is written as it is: the reader will ask for them.)
    validateScene(scene);
    TomlText t;
    if (!header.empty()) t.comment(header);
    t.table("units");
    t.string("length", scene.units.length);
    t.string("mass", scene.units.mass);
    t.string("time", scene.units.time);
    t.string("force", scene.units.force);
    for (const AssetSpec& a : scene.assets)
        if (a.set.empty()) writeAsset(t, a, sceneDirectory);
    // A set's assets are written as the set: the reader lists them again, after the others.
    for (const AssetSetSpec& s : scene.assetSets) {
        t.table("asset_sets." + TomlText::key(s.name));
        if (!s.catalog.empty()) t.string("catalog", pathFrom(sceneDirectory, s.catalog));
        else t.string("glob", pathFrom(sceneDirectory, s.glob));
        if (s.meshes) writeBakeKeys(t, s.bake, true);
    }
    for (const MaterialSpec& m : scene.materials) {
        t.table("materials." + TomlText::key(m.name));
        t.number("density", m.density);
    }
    for (const ContactSpec& c : scene.contacts) writeContact(t, scene, c);
    // Grains read from a CSV file are written as a reference to it (after the others, where
    // the reader puts them).
    std::vector<char> fromFile(scene.grains.size(), 0);
    for (const GrainFileSpec& f : scene.grainFiles)
        for (size_t i = f.first; i < f.first + f.count && i < fromFile.size(); ++i) fromFile[i] = 1;
    for (size_t i = 0; i < scene.grains.size(); ++i)
        if (!fromFile[i]) writeGrain(t, scene, scene.grains[i]);
    for (const GrainFileSpec& f : scene.grainFiles) {
        t.arrayTable("grain_files");
        t.string("file", pathFrom(sceneDirectory, f.file));
        t.string("material", scene.materials[size_t(f.material)].name);
        if (f.maxOverlap >= 0.0) t.number("max_overlap", f.maxOverlap);
    }
    for (const BoundarySpec& b : scene.boundaries) writeBoundary(t, scene, b);
    for (const MembraneSpec& m : scene.membranes) writeMembrane(t, scene, m, sceneDirectory);
    writeSimulation(t, scene);
    writeOutput(t, scene);
    return t.str();
}

void writeSceneFile(const Scene& scene, const std::string& path, const std::string& header)
{
    const fs::path folder = fs::absolute(path).parent_path();
    writeTextFileAtomically(path, sceneToToml(scene, folder.string(), header));
}

} // namespace lsdem
