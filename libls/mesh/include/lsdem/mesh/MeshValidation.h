/// @file MeshValidation.h
/// @brief Checks that a triangle mesh bounds a solid (closed, manifold, consistently and
///        outward oriented, no degenerate or non-finite data) and repairs what is safe to repair.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <string>
#include <vector>

namespace lsdem {

/// What validateSolidMesh found and did.
struct MeshValidationReport
{
    int removedDegenerateTriangles = 0;  ///< zero-area triangles dropped (their edges collapse)
    bool flippedToOutward = false;       ///< some part was inside-out and was reversed
    int reorientedTriangles = 0;         ///< triangles flipped to agree with their neighbours
};

/// Validate @a mesh as the boundary of a solid and repair it in place where that is safe:
/// - non-finite coordinates, an empty mesh, out-of-range indices: refuse;
/// - degenerate triangles (area below a tiny fraction of the mean): drop them;
/// - open surface (edges with one triangle): refuse, saying how many boundary edges;
/// - non-manifold edges (three or more triangles): refuse, saying how many;
/// - inconsistent orientation inside a connected part: flip the smaller set of triangles;
/// - a part that encloses no volume: refuse;
/// - two parts whose surfaces cross or touch (overlapping pieces not merged): refuse;
/// - an inside-out part: reverse it. Parts nested inside others (cavities) keep their
///   orientation relative to their outermost container, so hollow solids stay hollow.
/// @param source names the mesh in messages (usually its file path).
/// @throw Error with the file, the problem and the fix.
MeshValidationReport validateSolidMesh(TriangleMesh& mesh, const std::string& source);

/// The repairs in @a report as warnings naming @a source, appended to @a warnings (the bake
/// prints them: the asset is not quite the file).
void appendRepairWarnings(const MeshValidationReport& report, const std::string& source,
                          std::vector<std::string>& warnings);

} // namespace lsdem
