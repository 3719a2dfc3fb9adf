// Scenes in Python: read from TOML (file or text), written back as TOML, inspected, or built
// step by step from assets made in Python.
#include "Bindings.h"

#include "lsdem/contact/ContactCoefficients.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainCatalog.h"
#include "lsdem/scene/GrainsCsv.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem::python {

namespace {

namespace fs = std::filesystem;

/// Index of the entry called @a name in @a items; Error naming the kind and the choices.
template <typename Items>
int indexOf(const Items& items, const std::string& name, const std::string& kind)
{
    std::string known;
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) return static_cast<int>(i);
        known += (known.empty() ? "'" : ", '") + items[i].name + "'";
    }
    throw Error("", "no " + kind + " called '" + name + "'",
                known.empty() ? "add one first" : "use one of " + known);
}

template <typename Items>
void checkNewName(const Items& items, const std::string& name, const std::string& kind)
{
    if (name.empty()) throw Error("", "a " + kind + " needs a name");
    for (const auto& item : items)
        if (item.name == name)
            throw Error("", "there is already a " + kind + " called '" + name + "'",
                        "give each " + kind + " its own name");
}

double finite(double value, const std::string& what)
{
    if (!std::isfinite(value)) throw Error("", what + " must be finite");
    return value;
}

/// A unit quaternion (w, x, y, z) from Python; Error if it is not about unit length.
Quat toQuat(const py::handle& value)
{
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || a.ndim() != 1 || a.shape(0) != 4)
        throw Error("", "orientation must be four numbers [w, x, y, z]");
    const Quat q(a.at(0), a.at(1), a.at(2), a.at(3));
    if (!(std::abs(q.norm() - 1.0) < 1e-6))
        throw Error("", "orientation must be a unit quaternion", "normalize [w, x, y, z]");
    return q.normalized();
}

GrainMotion parseMotion(const std::string& motion)
{
    if (motion == "free") return GrainMotion::Free;
    if (motion == "fixed") return GrainMotion::Fixed;
    if (motion == "prescribed") return GrainMotion::Prescribed;
    throw Error("", "motion wants 'free', 'fixed' or 'prescribed', got '" + motion + "'");
}

/// A scene changed in Python no longer matches its file's text: drop it, so checkpoints store
/// the scene as it is now (its TOML) rather than as it was read.
void markChanged(Scene& s)
{
    s.text.clear();
}

} // namespace

Scene withSavedAssetFiles(const Scene& scene)
{
    Scene out = scene;
    for (AssetSpec& a : out.assets) {
        if (!a.file.empty() || !a.loaded) continue;
        a.file = rememberedAssetFile(a.loaded.get());
        if (a.file.empty())
            throw Error(a.where, "asset '" + a.name + "' is held only in memory",
                        "save it to a file first, e.g. asset.save('" + a.name + ".vdb') (before "
                        "or after scene.add_asset)");
    }
    return out;
}

namespace {

/// The folder a scene's relative paths are read from and written to.
std::string sceneFolder(const Scene& s)
{
    return s.directory.empty() ? fs::current_path().string() : s.directory;
}

/// @a file as an absolute path, relative ones from the scene's folder (as the reader does).
std::string scenePath(const Scene& s, const std::string& file)
{
    fs::path p(file);
    if (p.is_relative()) p = fs::path(sceneFolder(s)) / p;
    return fs::absolute(p).lexically_normal().string();
}

/// A plane's stress servo from the keyword arguments of add_plane (the checks of the scene
/// reader's [[boundaries]] servo keys, docs/scenes.md). Nothing unless @a stress is given.
void setServo(BoundarySpec& b, const std::optional<double>& stress,
              const std::optional<double>& area,
              const std::optional<std::vector<std::string>>& areaWalls,
              const std::optional<double>& maxSpeed, const std::optional<double>& gain)
{
    const std::string label = "boundary '" + b.name + "': ";
    if (!stress) {
        if (area || areaWalls || maxSpeed || gain)
            throw Error("", label + "area, area_walls, max_speed and servo_gain only make sense "
                                    "for a servo wall",
                        "add stress=σ (the target normal stress) or remove them");
        return;
    }
    StressServo& v = b.servo;
    if (!(*stress > 0.0) || !std::isfinite(*stress))
        throw Error("", label + "stress must be > 0: a wall can only push on the grains",
                    "give the compressive stress as a positive number (force/length²)");
    v.targetStress = *stress;
    if (!b.velocity.isZero(0.0))
        throw Error("", label + "a servo wall chooses its own velocity",
                    "remove velocity, or remove stress for a wall moving at a fixed velocity");
    if (area && areaWalls)
        throw Error("", label + "both area and area_walls are given", "keep one of them");
    if (!area && !areaWalls)
        throw Error("", label + "a servo wall needs the area its stress acts on",
                    "give area=A (length²) or area_walls=[x0, x1, y0, y1] (two pairs of "
                    "opposite walls around it, added before it)");
    if (area) {
        if (!(*area > 0.0) || !std::isfinite(*area))
            throw Error("", label + "area must be > 0");
        v.area = *area;
    } else {
        if (areaWalls->size() != 4)
            throw Error("", label + "area_walls wants the names of four walls",
                        "give two pairs of opposite walls, e.g. ['x0', 'x1', 'y0', 'y1']");
        b.areaWallNames = *areaWalls;
    }
    if (!maxSpeed || !(*maxSpeed > 0.0) || !std::isfinite(*maxSpeed))
        throw Error("", label + "a servo wall needs a limit speed max_speed > 0",
                    "give max_speed=v (length/time): how fast it may move towards its stress");
    v.maxSpeed = *maxSpeed;
    if (gain) {
        if (!(*gain > 0.0 && *gain <= 1.0))
            throw Error("", label + "servo_gain must be in (0, 1]",
                        "a gain above 1 overshoots the target every step; 0.5 is the default");
        v.gain = *gain;
    }
}

/// A boundary about an axis (a cylinder's side wall, an orifice plate), checked as the scene
/// reader checks it: a new name, a positive radius, a non-zero axis (made unit).
BoundarySpec axialBoundary(const Scene& s, const std::string& name, const std::string& material,
                           BoundaryShape shape, const py::object& center, double radius,
                           const py::object& axis, const py::object& velocity)
{
    checkNewName(s.boundaries, name, "boundary");
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw Error("", "boundary '" + name + "': radius must be > 0");
    BoundarySpec b;
    b.name = name;
    b.shape = shape;
    b.material = indexOf(s.materials, material, "material");
    b.center = toVec3(center, "center");
    b.axis = toVec3(axis, "axis");
    if (!(b.axis.norm() > 0.0))
        throw Error("", "boundary '" + name + "': the axis must not be zero");
    b.axis.normalize();
    b.radius = radius;
    b.velocity = toVec3(velocity, "velocity");
    b.where = "boundary '" + name + "'";
    return b;
}

template <typename Items>
std::vector<std::string> namesOf(const Items& items)
{
    std::vector<std::string> names;
    for (const auto& item : items) names.push_back(item.name);
    return names;
}

} // namespace

namespace {

/// Making, reading and writing a scene; its names and size.
void bindSceneFiles(py::class_<Scene>& scene)
{
    scene
        .def(py::init([] {
                 Scene s;
                 s.directory = fs::current_path().string();
                 return s;
             }),
             "An empty scene (units mm, tonne, s, N) whose relative paths are read from the "
             "current folder. Add assets, materials, contacts, grains and boundaries, and an "
             "end condition, before simulating it.")
        .def_static("from_toml",
                    [](const std::string& path) {
                        py::gil_scoped_release release;
                        return readSceneFile(path);
                    },
                    py::arg("path"),
                    "Read and check a scene file. Raises lsdem.Error with the file, line, key "
                    "and a fix for anything wrong.")
        .def_static("from_text",
                    [](const std::string& text, const std::string& path) {
                        return parseScene(text, path);
                    },
                    py::arg("text"), py::arg("path") = "scene.toml",
                    "Parse scene TOML text as if it were the file `path` (messages name it; "
                    "relative paths are resolved from its folder).")
        .def("to_toml",
             [](const Scene& s, std::optional<std::string> directory, const std::string& header) {
                 return sceneToToml(withSavedAssetFiles(s),
                                    directory ? *directory : sceneFolder(s), header);
             },
             py::arg("directory") = py::none(), py::arg("header") = "",
             "The scene as TOML text that from_text reads back to the same scene. Asset paths "
             "below `directory` (default: the scene's folder) are written relative to it. "
             "Assets made in Python must have been saved (Asset.save), before or after "
             "add_asset.")
        .def("save",
             [](const Scene& s, const std::string& path, const std::string& header) {
                 writeSceneFile(withSavedAssetFiles(s), path, header);
             },
             py::arg("path"), py::arg("header") = "",
             "Write the scene as a TOML file (atomically) that lsdem-run and from_toml read.")
        .def_readonly("path", &Scene::path, "The scene file, as given ('' if built in Python).")
        .def_readonly("directory", &Scene::directory, "The folder relative paths start from.")
        .def_readonly("text", &Scene::text, "The file's text; '' if built or changed in Python (to_toml() gives the "
                       "current scene).")
        .def_property_readonly(
            "units",
            [](const Scene& s) {
                py::dict d;
                d["length"] = s.units.length;
                d["mass"] = s.units.mass;
                d["time"] = s.units.time;
                d["force"] = s.units.force;
                return d;
            },
            "The declared unit system: dict of length, mass, time, force.")
        .def_property_readonly("asset_names", [](const Scene& s) { return namesOf(s.assets); })
        .def_property_readonly("material_names",
                               [](const Scene& s) { return namesOf(s.materials); })
        .def_property_readonly("grain_names", [](const Scene& s) { return namesOf(s.grains); },
                               "Grain names, '' for grains named by their index.")
        .def_property_readonly("boundary_names",
                               [](const Scene& s) { return namesOf(s.boundaries); })
        .def("__len__", [](const Scene& s) { return s.grains.size(); }, "The number of grains.");
    scene
        .def("__repr__", [](const Scene& s) {
            return "<lsdem.Scene '" + s.path + "': " + std::to_string(s.assets.size()) +
                   " assets, " + std::to_string(s.grains.size()) + " grains, " +
                   std::to_string(s.boundaries.size()) + " boundaries>";
        });
}

/// Gravity, damping, the time step and the end condition.
void bindSceneSettings(py::class_<Scene>& scene)
{
    scene
        .def_property(
            "gravity", [](const Scene& s) { return toArray(s.gravity); },
            [](Scene& s, const py::object& g) {
                const Vec3 gravity = toVec3(g, "gravity");
                markChanged(s);
                s.gravity = gravity;
            },
            "Gravity (3,), length/time².")
        .def_property(
            "global_damping", [](const Scene& s) { return s.globalDamping; },
            [](Scene& s, double d) {
                if (!(d >= 0.0 && d < 1.0))
                    throw Error("", "global_damping must be in [0, 1)",
                                "0 for none; about 0.1 to 0.3 for quasi-static loading");
                markChanged(s);
                s.globalDamping = d;
            },
            "Non-viscous damping λ in [0, 1) (as YADE's NewtonIntegrator).")
        .def_property(
            "time_step", [](const Scene& s) { return s.timeStep.fixed; },
            [](Scene& s, double dt) {
                if (!(dt >= 0.0) || !std::isfinite(dt))
                    throw Error("", "time_step must be >= 0 (0: automatic)");
                markChanged(s);
                s.timeStep.fixed = dt;
            },
            "The fixed time step, or 0 for automatic (safety · 2·sqrt(m/k)).")
        .def_property(
            "end_time", [](const Scene& s) { return s.end.time; },
            [](Scene& s, double t) {
                if (!(finite(t, "end_time") >= 0.0))
                    throw Error("", "end_time must be >= 0, got " + std::to_string(t),
                                "0 for no time limit");
                markChanged(s);
                s.end.time = t;
            },
            "Stop at this simulated time (0: no time limit).")
        .def_property(
            "end_steps", [](const Scene& s) { return s.end.steps; },
            [](Scene& s, long long n) {
                if (n < 0)
                    throw Error("", "end_steps must be >= 0, got " + std::to_string(n),
                                "0 for no step limit");
                markChanged(s);
                s.end.steps = n;
            },
            "Stop after this many steps (0: no step limit).")
        .def("set_end_displacement",
             [](Scene& s, const std::string& boundary, double value) {
                 if (!(value > 0.0) || !std::isfinite(value))
                     throw Error("", "end displacement must be > 0");
                 const int index = indexOf(s.boundaries, boundary, "boundary");
                 const BoundarySpec& moved = s.boundaries[static_cast<size_t>(index)];
                 if (!(moved.velocity.norm() > 0.0) && !moved.servo.active())
                     throw Error("", "boundary '" + boundary +
                                         "' does not move, so it never reaches the displacement",
                                 "give it a velocity or a stress, or set end_time / end_steps");
                 markChanged(s);
                 s.end.boundary = index;
                 s.end.displacement = value;
             },
             py::arg("boundary"), py::arg("value"),
             "Stop when the named (moving) boundary has moved this far (length).");
}

/// Assets, materials, contact laws and grains, one by one.
void bindSceneContents(py::class_<Scene>& scene)
{
    scene
        .def("add_asset",
             [](Scene& s, const std::string& name, const AssetHandle& asset) {
                 checkNewName(s.assets, name, "asset");
                 markChanged(s);
                 AssetSpec spec;
                 spec.name = name;
                 spec.loaded = asset.asset;
                 if (!asset.path.empty()) spec.file = fs::absolute(asset.path).string();
                 spec.where = "asset '" + name + "'";
                 s.assets.push_back(spec);
             },
             py::arg("name"), py::arg("asset"),
             "Use an Asset (baked or loaded in Python) under this name. to_toml writes the "
             "file it was loaded from or saved to.")
        .def("add_material",
             [](Scene& s, const std::string& name, double density) {
                 checkNewName(s.materials, name, "material");
                 if (!(density >= 0.0) || !std::isfinite(density))
                     throw Error("", "material '" + name + "': density must be >= 0");
                 markChanged(s);
                 s.materials.push_back({name, density});
             },
             py::arg("name"), py::arg("density") = 0.0,
             "A material: density in mass/length³ (> 0 for free grains; boundaries need none).")
        .def("add_contact",
             [](Scene& s, const std::string& a, const std::string& b,
                const std::string& formulation, double normalStiffness, double shearStiffness,
                double friction, double restitution, const std::string& testing) {
                 ContactSpec c;
                 c.materialA = indexOf(s.materials, a, "material");
                 c.materialB = indexOf(s.materials, b, "material");
                 for (const ContactSpec& other : s.contacts)
                     if (std::minmax(other.materialA, other.materialB) ==
                         std::minmax(c.materialA, c.materialB))
                         throw Error("", "there is already a contact law between materials '" +
                                             a + "' and '" + b + "'",
                                     "give each pair of materials one law");
                 c.model.formulation = parseFormulation(formulation);
                 c.model.testing = parseNodeTesting(testing);
                 // The contact library's schema checks the numbers, as the scene reader does.
                 const std::pair<const char*, double> given[] = {
                     {"normal_stiffness", normalStiffness}, {"shear_stiffness", shearStiffness},
                     {"friction", friction}, {"restitution", restitution}};
                 for (const ContactCoefficient& k : contactCoefficients()) {
                     const auto value = std::find_if(std::begin(given), std::end(given),
                                                     [&](const auto& g) { return k.key == g.first; });
                     if (value == std::end(given))  // a coefficient added to the schema only
                         throw std::logic_error("add_contact does not take " + k.key);
                     if (std::optional<ContactProblem> p = k.rangeProblem(value->second))
                         throw Error("", p->key + " " + p->problem, p->fix);
                     k.set(c.model, value->second);
                 }
                 if (std::optional<ContactProblem> p = checkContactModel(c.model, "'"))
                     throw Error("", p->key + " " + p->problem, p->fix);
                 markChanged(s);
                 c.where = "contact " + a + "-" + b;
                 s.contacts.push_back(c);
             },
             py::arg("material_a"), py::arg("material_b"), py::kw_only(),
             py::arg("formulation") = "adapted", py::arg("normal_stiffness"),
             py::arg("shear_stiffness") = contactCoefficientDefault("shear_stiffness"),
             py::arg("friction") = contactCoefficientDefault("friction"),
             py::arg("restitution") = contactCoefficientDefault("restitution"),
             py::arg("testing") = "symmetric",
             "The contact law between two materials: formulation ('adapted', 'original', "
             "'single-node', 'volume'), normal_stiffness (kn or kn*, see docs/contact.md), "
             "shear springs, friction, restitution in (0, 1] (1: no damping) and node testing "
             "('symmetric' or 'one-way').")
        .def("add_grain",
             [](Scene& s, const std::string& asset, const std::string& material,
                const py::object& position, const py::object& orientation,
                const py::object& velocity, const py::object& angularVelocity, double mass,
                const std::string& motion, const std::string& name) {
                 GrainSpec g;
                 g.asset = indexOf(s.assets, asset, "asset");
                 g.material = indexOf(s.materials, material, "material");
                 g.pose.position = toVec3(position, "position");
                 g.pose.orientation = toQuat(orientation);
                 g.velocity = toVec3(velocity, "velocity");
                 g.angularVelocity = toVec3(angularVelocity, "angular_velocity");
                 if (!(finite(mass, "mass") >= 0.0))
                     throw Error("", "mass must be >= 0, got " + std::to_string(mass),
                                 "0 to take density × volume");
                 g.mass = mass;
                 g.motion = parseMotion(motion);
                 if (g.motion == GrainMotion::Fixed &&
                     (g.velocity.norm() > 0.0 || g.angularVelocity.norm() > 0.0))
                     throw Error("", "a fixed grain may not have a velocity",
                                 "use motion='prescribed' to move it at that velocity");
                 if (!name.empty()) checkNewName(s.grains, name, "grain");
                 g.name = name;
                 g.where = "grain " + std::to_string(s.grains.size());
                 markChanged(s);
                 s.grains.push_back(g);
                 return s.grains.size() - 1;
             },
             py::arg("asset"), py::arg("material"), py::arg("position"), py::kw_only(),
             py::arg("orientation") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("angular_velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("mass") = 0.0, py::arg("motion") = "free", py::arg("name") = "",
             "Place a grain of a named asset and material: position of its centroid, "
             "orientation as a unit quaternion [w, x, y, z] (asset frame to world), initial "
             "velocity and angular velocity (world), mass (> 0 overrides density × volume), "
             "motion ('free', 'fixed', 'prescribed'). Returns its index.");
}

/// Walls, containers, an orifice plate and an indenter.
void bindSceneBoundaries(py::class_<Scene>& scene)
{
    scene
        .def("add_plane",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& point, const py::object& normal, const py::object& velocity,
                std::optional<double> stress, std::optional<double> area,
                std::optional<std::vector<std::string>> areaWalls,
                std::optional<double> maxSpeed, std::optional<double> servoGain) {
                 checkNewName(s.boundaries, name, "boundary");
                 BoundarySpec b;
                 b.name = name;
                 b.shape = BoundaryShape::Plane;
                 b.material = indexOf(s.materials, material, "material");
                 b.point = toVec3(point, "point");
                 b.normal = toVec3(normal, "normal");
                 if (!(b.normal.norm() > 0.0)) throw Error("", "the normal must not be zero");
                 b.normal.normalize();
                 b.velocity = toVec3(velocity, "velocity");
                 b.where = "boundary '" + name + "'";
                 setServo(b, stress, area, areaWalls, maxSpeed, servoGain);
                 s.boundaries.push_back(b);
                 if (!b.areaWallNames.empty()) {
                     try {  // the walls it names must be in the scene already
                         resolveServoAreaWalls(s);
                     } catch (const Error&) {
                         s.boundaries.pop_back();
                         throw;
                     }
                 }
                 markChanged(s);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("point"),
             py::arg("normal"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("stress") = py::none(), py::arg("area") = py::none(),
             py::arg("area_walls") = py::none(), py::arg("max_speed") = py::none(),
             py::arg("servo_gain") = py::none(),
             "An unbounded wall through `point`; grains live on the side `normal` points to. "
             "It moves at `velocity` whatever the forces (zero: fixed).\n\n"
             "With `stress` (> 0, force/length²) it is a servo wall instead (docs/packing.md): "
             "it moves along its normal to keep the grains' normal stress on it, over `area` "
             "(length²) or over the rectangle between `area_walls` (the names of two pairs of "
             "opposite plane walls perpendicular to it, added before it), at most at "
             "`max_speed` (required), closing the share `servo_gain` in (0, 1] (default 0.5) "
             "of the error per step.")
        .def("add_cylinder_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, const py::object& axis,
                const py::object& velocity) {
                 BoundarySpec b = axialBoundary(s, name, material, BoundaryShape::Cylinder,
                                                center, radius, axis, velocity);
                 markChanged(s);
                 s.boundaries.push_back(b);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "The side wall of an infinitely long cylinder through `center` along `axis`; "
             "grains live inside it (a container: add planes for its floor and lid).")
        .def("add_orifice_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, double thickness,
                const py::object& axis, const py::object& velocity) {
                 BoundarySpec b = axialBoundary(s, name, material, BoundaryShape::Orifice,
                                                center, radius, axis, velocity);
                 if (!(thickness > 0.0) || !std::isfinite(thickness))
                     throw Error("", "boundary '" + name + "': thickness must be > 0");
                 b.thickness = thickness;
                 markChanged(s);
                 s.boundaries.push_back(b);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("thickness"),
             py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "A flat plate of `thickness` with a circular hole of `radius` (a silo's floor "
             "and its orifice): `center` is the hole's centre in the plate's mid-plane, `axis` "
             "the plate's normal; grains live outside the plate, on either side.");
    scene
        .def("add_sphere_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, const py::object& velocity) {
                 checkNewName(s.boundaries, name, "boundary");
                 if (!(radius > 0.0) || !std::isfinite(radius))
                     throw Error("", "boundary '" + name + "': radius must be > 0");
                 BoundarySpec b;
                 b.name = name;
                 b.shape = BoundaryShape::Sphere;
                 b.material = indexOf(s.materials, material, "material");
                 b.center = toVec3(center, "center");
                 b.radius = radius;
                 b.velocity = toVec3(velocity, "velocity");
                 b.where = "boundary '" + name + "'";
                 markChanged(s);
                 s.boundaries.push_back(b);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "A rigid sphere (an indenter); grains live outside it.");
}

/// Assets and grains from files: a catalogue's asset set and a grains CSV.
void bindSceneFileSources(py::class_<Scene>& scene)
{
    scene
        .def("add_asset_set",
             [](Scene& s, const std::string& name, const std::string& catalog) {
                 if (name.empty() || name.find('/') != std::string::npos)
                     throw Error("", "an asset set's name must be non-empty and hold no '/'",
                                 "its assets are named SET/ASSET; e.g. 'sand'");
                 checkNewName(s.assetSets, name, "asset set");
                 AssetSetSpec set;
                 set.name = name;
                 set.catalog = scenePath(s, catalog);
                 set.where = "asset set '" + name + "'";
                 std::error_code ec;
                 if (!fs::is_regular_file(set.catalog, ec))
                     throw Error(set.catalog, "catalogue not found",
                                 "give the catalog.csv lsdem-bake --out-dir wrote (relative "
                                 "paths are from the scene's folder)");
                 const std::vector<CatalogEntry> entries = readCatalog(set.catalog);
                 if (entries.empty())
                     throw Error(set.catalog, "the catalogue lists no assets",
                                 "bake some files into its folder with lsdem-bake --out-dir");
                 const fs::path folder = fs::path(set.catalog).parent_path();
                 std::vector<AssetSpec> added;
                 for (const CatalogEntry& e : entries) {
                     AssetSpec a;
                     a.name = name + "/" + e.name;
                     fs::path file(e.asset);
                     if (file.is_relative()) file = folder / file;
                     a.file = fs::absolute(file).lexically_normal().string();
                     if (!fs::is_regular_file(a.file, ec))
                         throw Error(set.catalog,
                                     "asset '" + e.name + "': file not found: " + a.file,
                                     "bake the set again (lsdem-bake --out-dir), or fix its "
                                     "asset column");
                     checkNewName(s.assets, a.name, "asset");
                     a.set = name;
                     a.where = set.where;
                     added.push_back(std::move(a));
                 }
                 markChanged(s);
                 std::vector<std::string> names;
                 for (AssetSpec& a : added) {
                     names.push_back(a.name);
                     s.assets.push_back(std::move(a));
                 }
                 s.assetSets.push_back(std::move(set));
                 return names;
             },
             py::arg("name"), py::kw_only(), py::arg("catalog"),
             "Every asset of a catalogue (lsdem-bake --out-dir writes DIR/catalog.csv), named "
             "'NAME/ASSET', as [asset_sets.NAME] catalog = ... does; they are loaded when the "
             "scene is simulated. Returns their names. (The TOML reader lists a set's assets "
             "after the [assets] tables: add sets after single assets for to_toml to read back "
             "in the same order.)")
        .def("add_grain_file",
             [](Scene& s, const std::string& file, const std::string& material,
                std::optional<double> maxOverlap) {
                 GrainFileSpec f;
                 f.file = scenePath(s, file);
                 f.material = indexOf(s.materials, material, "material");
                 if (maxOverlap) {
                     if (!(*maxOverlap >= 0.0) || !std::isfinite(*maxOverlap))
                         throw Error("", "max_overlap must be >= 0 (a length)");
                     f.maxOverlap = *maxOverlap;
                 }
                 f.where = "grain file '" + f.file + "'";
                 std::ifstream in(f.file, std::ios::binary);
                 std::error_code ec;
                 if (!in || fs::is_directory(f.file, ec))
                     throw Error(f.file, "cannot read the grains table",
                                 "give a path relative to the scene's folder or an absolute one");
                 std::ostringstream text;
                 text << in.rdbuf();
                 Scene copy = s;  // the scene is unchanged if a row is refused
                 f.first = copy.grains.size();
                 readGrainsCsv(text.str(), f.file, f.material, copy);
                 f.count = copy.grains.size() - f.first;
                 if (f.count == 0)
                     throw Error(f.file, "the table holds no grains",
                                 "add a row per grain below the header");
                 copy.grainFiles.push_back(f);
                 markChanged(copy);
                 s = std::move(copy);
                 return f.count;
             },
             py::arg("file"), py::arg("material"), py::kw_only(),
             py::arg("max_overlap") = py::none(),
             "The grains of a CSV table (lsdem-pack's output, a CT scan, another code: asset, "
             "x, y, z, qw, qx, qy, qz, optional name, material, velocities), as [[grain_files]] "
             "does: assets and materials by name, `material` for rows without one; overlaps "
             "beyond max_overlap (a length; default 5 % of the smaller bounding radius) are "
             "refused when the scene is simulated. Returns the number of grains. (The TOML "
             "reader puts file grains after [[grains]]: add files last for to_toml to read back "
             "in the same order.)");
}

} // namespace

void bindScenes(py::module_& m)
{
    py::class_<Scene> scene(
        m, "Scene",
        "A simulation scene: assets, materials, contact laws, grains, boundaries, time "
        "stepping and the end condition (docs/scenes.md is the reference).\n\n"
        "Read one with Scene.from_toml(path) or Scene.from_text(text); build one with Scene() "
        "and the add_* methods; write it with to_toml() or save(path). Relative paths in a "
        "scene are resolved from its folder (the file's, or the current one for a scene built "
        "in Python). Changing a scene does not change simulations made from it.");
    bindSceneFiles(scene);
    bindSceneSettings(scene);
    bindSceneContents(scene);
    bindSceneBoundaries(scene);
    bindSceneFileSources(scene);
}

} // namespace lsdem::python
