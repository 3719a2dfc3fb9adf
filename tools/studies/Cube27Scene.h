/// @file Cube27Scene.h
/// @brief The scene of one run of the 3×3×3 stack study: 27 spheres filling a box of six
///        plane walls, the top one moving down.
#pragma once

#include "studies/Cube27Plan.h"

#include "lsdem/ls/GrainAsset.h"
#include "lsdem/scene/Scene.h"

#include <memory>

namespace lsdem {

/// The scene of one run: 27 spheres (@a sphere, the baked asset held in memory; or, if null,
/// an analytic sphere baked at load), randomly oriented per grain from the run's orientation
/// seed, six plane walls, the contact model, no gravity, global damping, the planned time step
/// and end displacement.
Scene makeCube27Scene(const Cube27Options& o, const Cube27Run& run,
                      std::shared_ptr<const GrainAsset> sphere = nullptr);

} // namespace lsdem
