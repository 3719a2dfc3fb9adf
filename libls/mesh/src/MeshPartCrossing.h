/// @file MeshPartCrossing.h
/// @brief Whether two parts (connected components) of a closed triangle mesh cross or touch
///        each other. A solid's surface may hold several parts (a grain with a cavity, a
///        grain in one piece beside another), but not parts that overlap: a clump of
///        primitives exported without a boolean union counts the overlap twice in its mass
///        properties, and its level set has a false surface inside the solid.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <optional>
#include <vector>

namespace lsdem {

/// One part of a mesh: its triangles and bounding box.
struct MeshPart
{
    const std::vector<int>* triangles = nullptr;
    Vec3 lo, hi;
};

struct PartCrossing
{
    int partA = -1, partB = -1;        ///< indices into the parts given, partA < partB
    int triangleA = -1, triangleB = -1;  ///< a pair of their triangles that meet
};

/// A pair of triangles of two different parts of @a mesh that intersect (share a point,
/// with exact predicates): the least such pair, by parts and then triangles; none if no two
/// parts meet.
std::optional<PartCrossing> findPartCrossing(const TriangleMesh& mesh,
                                             const std::vector<MeshPart>& parts);

} // namespace lsdem
