/// @file GrainOverlaps.h
/// @brief How deep grains overlap, measured as the contact laws see it: the deepest node of
///        either grain inside the other's level set (−φ at that node). Used to check packings
///        read from a file or generated, where bounding spheres would overlap for any pair of
///        neighbouring elongated grains.
#pragma once

#include "lsdem/simulation/World.h"

#include <vector>

namespace lsdem {

struct GrainOverlap
{
    int first = 0, second = 0;  ///< grain indices, first < second
    double depth = 0.0;         ///< deepest node penetration, either way (length, > 0)
};

/// Every pair of grains of @a world that overlaps (some node of one inside the other), sorted
/// by pair. Candidate pairs come from the bounding spheres; pairs are measured in parallel
/// (the result does not depend on the thread count).
std::vector<GrainOverlap> findGrainOverlaps(const World& world);

} // namespace lsdem
