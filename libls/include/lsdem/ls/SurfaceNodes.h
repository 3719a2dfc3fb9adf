/// @file SurfaceNodes.h
/// @brief The surface nodes of a grain: quadrature points of the contact traction integral,
///        each with a position, an outward unit normal and a tributary area.
#pragma once

#include "lsdem/ls/TriangleMesh.h"

#include <vector>

namespace lsdem {

enum class AreaRule {
    Mesh,     ///< one third of each incident triangle's area (sums to the mesh area)
    Uniform,  ///< total mesh area / N for every node, as in the paper
};

struct SurfaceNodes
{
    std::vector<Vec3> positions;  ///< length, in the grain's principal frame
    std::vector<Vec3> normals;    ///< unit, outward
    std::vector<double> areas;    ///< length^2, tributary areas

    size_t size() const { return positions.size(); }
    double totalArea() const;
};

/// Nodes at the vertices of @a mesh, areas by @a rule, normals angle-weighted from the faces.
/// Vertices no triangle uses are dropped.
SurfaceNodes nodesFromMesh(const TriangleMesh& mesh, AreaRule rule);

/// Reorder nodes along a Morton (Z-order) curve of cells of size @a cellSize, so neighbours in
/// the array are neighbours in space and level-set lookups stay cache-friendly.
void sortNodesSpatially(SurfaceNodes& nodes, double cellSize);

/// A run of consecutive nodes (in Morton order, so close together) and a sphere holding them:
/// the narrow phase skips a whole block when the sphere is clear of the other grain.
struct NodeBlock
{
    int begin = 0, end = 0;       ///< node indices [begin, end)
    Vec3 center = Vec3::Zero();   ///< of the block's bounding sphere, asset frame
    double radius = 0.0;
};

/// Cut the (spatially sorted) nodes into runs of at most @a blockSize with bounding spheres.
std::vector<NodeBlock> groupNodesIntoBlocks(const SurfaceNodes& nodes, int blockSize = 32);

/// Spacing statistics: for each node, the distance to its nearest other node.
struct NodeSpacing
{
    double mean = 0.0, min = 0.0, max = 0.0;
};
NodeSpacing nodeSpacing(const SurfaceNodes& nodes);

} // namespace lsdem
