/// @file BroadPhase.h
/// @brief Candidate pairs of grains whose bounding spheres overlap, found with a uniform cell
///        grid so the cost grows with the number of grains and near pairs, not grains².
#pragma once

#include "lsdem/core/Vec3.h"

#include <utility>
#include <vector>

namespace lsdem {

/// Pairs (i, j), i < j, with |c_i - c_j| <= r_i + r_j + margin, sorted, so the list (and
/// everything computed from it) does not depend on hashing or thread order.
std::vector<std::pair<int, int>> findCandidatePairs(const std::vector<Vec3>& centers,
                                                    const std::vector<double>& radii,
                                                    double margin = 0.0);

} // namespace lsdem
