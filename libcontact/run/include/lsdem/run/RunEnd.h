/// @file RunEnd.h
/// @brief When a run stops: the first of the scene's end conditions (time, steps, boundary
///        displacement) that the world has met. lsdem-run and the Python module both stop
///        here, so they take the same number of steps.
#pragma once

#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

namespace lsdem {

/// Whether @a w has met the first of @a scene's end conditions, stepping by @a dt (the time
/// condition allows a round-off of 1e-9 dt, so a run ending on a step boundary stops there).
bool endReached(const Scene& scene, const World& w, double dt);

} // namespace lsdem
