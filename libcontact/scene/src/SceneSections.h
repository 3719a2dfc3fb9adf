/// @file SceneSections.h
/// @brief The readers of the sections of a scene file (private to the scene reader), one file
///        each: units, assets, grains and lattices, contacts, boundaries, simulation and output,
///        and the checks across sections.
#pragma once

#include "SceneChecks.h"
#include "TableReader.h"

#include "lsdem/scene/Scene.h"

#include <string>
#include <vector>

namespace lsdem::scenefile {

/// [units]: the declared system, checked for force = mass·length/time². Null: the defaults.
UnitSystem readUnits(const toml::table* table, const std::string& path);

/// [assets.NAME]: a baked file, or a mesh or shape baked at load with its options.
AssetSpec readAsset(const std::string& name, const toml::table& table, const Scene& scene);

/// The baking keys of an asset or set (voxel, node_spacing | nodes | mesh_nodes, areas) into
/// @a bake; @a analytic refuses mesh_nodes; @a provenance starts the options text.
void readBakeKeys(TableReader& t, BakeOptions& bake, bool analytic, const std::string& provenance);

/// @a file (as written in the scene) resolved from the scene's @a directory, absolute.
std::string resolveScenePath(const std::string& directory, const std::string& file);

/// [asset_sets.NAME]: a catalogue or a glob of baked assets, appended to scene.assets and
/// recorded in scene.assetSets.
void readAssetSet(const std::string& name, const toml::table& table, Scene& scene);

/// The most grains a scene may hold (single grains and lattices together): far more than lsdem
/// can simulate on one machine, and a bound on what a few bytes of [[lattices]] can ask for.
constexpr long long kMaxSceneGrains = 1000000;

/// [[grains]]: one grain.
GrainSpec readGrain(TableReader& t, const Scene& scene);
/// [[lattices]]: a block of grains, appended to @a scene.
void readLattice(TableReader& t, Scene& scene);
/// [[grain_files]]: the grains of a CSV table (GrainsCsv.h), appended to @a scene.
void readGrainFile(TableReader& t, Scene& scene);
/// orientation = [w, x, y, z] or axis_angle = [ax, ay, az, degrees]; identity if neither.
Quat readOrientation(TableReader& t);

/// [[contacts]]: the contact law between two materials.
ContactSpec readContact(TableReader& t, const Scene& scene);

/// [[boundaries]]: a plane, a sphere or a level-set obstacle.
BoundarySpec readBoundary(TableReader& t, const Scene& scene);

/// [[membranes]]: a membrane round the grains (MembraneKeys.h), its holding boundaries
/// looked up among those read before it.
MembraneSpec readMembrane(TableReader& t, const Scene& scene);

/// [simulation]: gravity, damping, time step and the end condition (required).
void readSimulation(const toml::table* table, Scene& scene);
/// [output]: history, ParaView and checkpoint periods (optional).
void readOutput(const toml::table* table, Scene& scene);

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
        // A few names are a hint; a set of a thousand assets would bury the message.
        constexpr size_t kShown = 12;
        std::vector<std::string> names;
        for (size_t k = 0; k < specs.size() && k < kShown; ++k)
            names.push_back("'" + specs[k].name + "'");
        if (specs.size() > kShown)
            names.push_back("... (" + std::to_string(specs.size()) + " in all)");
        t.fail(key, "no " + what + " named '" + name + "'",
               (names.empty() ? "" : "use one of " + joined(names) + ", or ") + howToDefine);
    }
    return i;
}

inline int lookUpAsset(TableReader& t, const Scene& scene)
{
    return lookUp(t, "asset", scene.assets, "asset",
                  "define it in an [assets.NAME] table (or an [asset_sets.SET] table, whose "
                  "assets are named SET/NAME)");
}

inline int lookUpMaterial(TableReader& t, const Scene& scene)
{
    return lookUp(t, "material", scene.materials, "material",
                  "define it in a [materials.NAME] table");
}

} // namespace lsdem::scenefile
