/// @file BuildWorld.h
/// @brief From a scene description to the state of a simulation: load (or bake) its assets,
///        place its grains and boundaries, and set the contact model of every pair of
///        materials.
#pragma once

#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

#include <memory>
#include <string>
#include <vector>

namespace lsdem {

/// Load (or bake) every asset of @a scene and place its grains and boundaries. The assets load
/// in parallel, at most one per thread at a time (so meshes baked at load hold up to one bake's
/// memory per thread), with the outcome of one by one. Messages that do not stop the run (from
/// baking) are appended to @a warnings, in the assets' order.
/// @throw Error naming the scene entry for anything that cannot be loaded or made (of several,
/// the first in the scene's order), or for a pair of materials that can meet without a contact
/// law (the check the scene file reader makes, for scenes built in code).
World buildWorld(const Scene& scene, std::vector<std::string>& warnings);

/// The runtime boundary for @a spec (@a asset: the loaded asset of a level-set obstacle).
Boundary makeBoundary(const BoundarySpec& spec, std::shared_ptr<const GrainAsset> asset);

} // namespace lsdem
