// Scenes in Python: read from TOML (file or text), written back as TOML, inspected, or built
// step by step from assets made in Python. This file: the class, making, reading and writing a
// scene, its settings, and the helpers the builder methods share (SceneBuilding.h); the
// builder methods are in SceneContentBindings.cpp, SceneBoundaryBindings.cpp and
// SceneSourceBindings.cpp.
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"

#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem::python {

namespace fs = std::filesystem;

double finite(double value, const std::string& what)
{
    if (!std::isfinite(value)) throw Error("", what + " must be finite");
    return value;
}

Quat toQuat(const py::handle& value)
{
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || a.ndim() != 1 || a.shape(0) != 4)
        throw Error("", "orientation must be four numbers [w, x, y, z]");
    const Quat q(a.at(0), a.at(1), a.at(2), a.at(3));
    if (!(std::abs(q.norm() - 1.0) < 1e-6))
        throw Error("", "orientation must be a unit quaternion", "normalize [w, x, y, z]");
    return unitQuaternion(q);
}

GrainMotion parseMotion(const std::string& motion)
{
    if (motion == "free") return GrainMotion::Free;
    if (motion == "fixed") return GrainMotion::Fixed;
    if (motion == "prescribed") return GrainMotion::Prescribed;
    throw Error("", "motion wants 'free', 'fixed' or 'prescribed', got '" + motion + "'");
}

void markChanged(Scene& s)
{
    s.text.clear();
}

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

std::string sceneFolder(const Scene& s)
{
    return s.directory.empty() ? fs::current_path().string() : s.directory;
}

std::string scenePath(const Scene& s, const std::string& file)
{
    fs::path p(file);
    if (p.is_relative()) p = fs::path(sceneFolder(s)) / p;
    return fs::absolute(p).lexically_normal().string();
}

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
