// Scenes in Python: read from TOML (file or text), written back as TOML, inspected, or built
// step by step from assets made in Python. This file: the class, making, reading and writing a
// scene, its settings, and the helpers the builder methods share (SceneBuilding.h); the
// builder methods are in SceneContentBindings.cpp, SceneBoundaryBindings.cpp and
// SceneSourceBindings.cpp.
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneSettings.h"
#include "lsdem/scene/SceneWriter.h"

#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem::python {

namespace fs = std::filesystem;

Quat toQuat(const py::handle& value)
{
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || a.ndim() != 1 || a.shape(0) != 4)
        throw Error("", "orientation must be four numbers [w, x, y, z]");
    const Quat q(a.at(0), a.at(1), a.at(2), a.at(3));
    if (std::optional<std::string> p = orientationProblem(q))
        throw Error("", "orientation " + *p, kOrientationFix);
    return unitQuaternion(q);
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

/// A setting's value for Python: a float, an int, a bool or an array (3,).
py::object settingToPython(const SettingValue& value)
{
    if (const double* d = std::get_if<double>(&value)) return py::float_(*d);
    if (const long long* n = std::get_if<long long>(&value)) return py::int_(*n);
    if (const bool* b = std::get_if<bool>(&value)) return py::bool_(*b);
    return toArray(std::get<Vec3>(value));
}

/// A Python value as @a setting's type: ints for counts, bools for flags (not a number that
/// happens to be 0 or 1), three numbers for a vector.
SettingValue settingFromPython(const SceneSetting& setting, const py::handle& value)
{
    const SettingValue kind = setting.defaultValue();
    if (std::holds_alternative<Vec3>(kind)) return toVec3(value, setting.key);
    if (std::holds_alternative<bool>(kind)) {
        if (!py::isinstance<py::bool_>(value))
            throw Error("", setting.key + " must be True or False", "");
        return value.cast<bool>();
    }
    if (std::holds_alternative<long long>(kind)) {
        if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
            throw Error("", setting.key + " must be a whole number", "");
        return value.cast<long long>();
    }
    if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value))
        throw Error("", setting.key + " must be a number", "");
    return value.cast<double>();
}

void bindSceneSettings(py::class_<Scene>& scene)
{
    // One property per setting of [simulation] and [output], with the file's name, range and
    // advice (SceneSettings.h); the setter refuses what a file would.
    for (const SceneSetting& setting : sceneSettings()) {
        const SceneSetting* s = &setting;  // the schema lives as long as the program
        scene.def_property(
            s->key.c_str(), [s](const Scene& sc) { return settingToPython(s->get(sc)); },
            [s](Scene& sc, const py::object& value) {
                const SettingValue v = settingFromPython(*s, value);
                checkSetting(*s, v, "");
                markChanged(sc);
                s->set(sc, v);
            },
            ("[" + s->section + "] " + s->doc).c_str());
    }
    scene
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
    bindSceneMembranes(scene);
    bindSceneFileSources(scene);
}

} // namespace lsdem::python
