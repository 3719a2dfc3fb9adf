// What the Python module's scene binding files share (SceneBindings.cpp, SceneContentBindings.cpp,
// SceneBoundaryBindings.cpp, SceneSourceBindings.cpp): the lookups and checks the builder
// methods make as the scene reader makes them, and one bind function per group of methods.
#pragma once

#include "Bindings.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/Scene.h"

#include <string>
#include <vector>

namespace lsdem::python {

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

template <typename Items>
std::vector<std::string> namesOf(const Items& items)
{
    std::vector<std::string> names;
    for (const auto& item : items) names.push_back(item.name);
    return names;
}

/// A unit quaternion (w, x, y, z) from Python; Error if it is not about unit length.
Quat toQuat(const py::handle& value);
/// A scene changed in Python no longer matches its file's text: drop it, so checkpoints store
/// the scene as it is now (its TOML) rather than as it was read.
void markChanged(Scene& s);
/// The folder a scene's relative paths are read from and written to.
std::string sceneFolder(const Scene& s);
/// @a file as an absolute path, relative ones from the scene's folder (as the reader does).
std::string scenePath(const Scene& s, const std::string& file);

/// Making, reading and writing a scene; its names and size (SceneBindings.cpp).
void bindSceneFiles(py::class_<Scene>& scene);
/// Gravity, damping, the time step and the end condition (SceneBindings.cpp).
void bindSceneSettings(py::class_<Scene>& scene);
/// Assets, materials, contact laws and grains, one by one (SceneContentBindings.cpp).
void bindSceneContents(py::class_<Scene>& scene);
/// Walls, containers, an orifice plate and an indenter (SceneBoundaryBindings.cpp).
void bindSceneBoundaries(py::class_<Scene>& scene);
/// A rubber membrane round the grains (SceneMembraneBindings.cpp).
void bindSceneMembranes(py::class_<Scene>& scene);
/// Assets and grains from files: a catalogue's asset set and a grains CSV
/// (SceneSourceBindings.cpp).
void bindSceneFileSources(py::class_<Scene>& scene);

} // namespace lsdem::python
