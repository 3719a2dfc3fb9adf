/// @file SampleElimination.h
/// @brief An evenly spread subset of many random points on a surface: Yuksel's weighted
///        sample elimination (Computer Graphics Forum 34(2), 2015), which removes, one at a
///        time, the point most crowded by its neighbours until the wanted count is left.
#pragma once

#include "lsdem/core/Vec3.h"

#include <cstddef>
#include <vector>

namespace lsdem {

/// The indices (increasing) of @a count of @a candidates, points spread over a surface of
/// area @a area, chosen so that none has a close neighbour. Deterministic: ties go to the
/// lower index. @a count must be at most candidates.size().
std::vector<int> eliminateSamples(const std::vector<Vec3>& candidates, size_t count, double area);

} // namespace lsdem
