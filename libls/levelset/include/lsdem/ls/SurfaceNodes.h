/// @file SurfaceNodes.h
/// @brief The surface nodes of a grain: quadrature points of the contact traction integral,
///        each with a position, an outward unit normal and a tributary area.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <vector>

namespace lsdem {

enum class AreaRule {
    Mesh,     ///< one third of each incident triangle's area (sums to the mesh area)
    Uniform,  ///< total mesh area / N for every node, as in the paper
};

struct SurfaceNodes
{
    std::vector<Vec3> positions;  ///< length, in the grain's principal frame
    /// Unit, outward; or none at all in the assets a simulation holds: no contact law reads
    /// them, and at 24 bytes a node they are a tenth of a small grain's asset (dropNormals,
    /// loadAsset with NodeNormals::Skip).
    std::vector<Vec3> normals;
    std::vector<double> areas;    ///< length^2, tributary areas

    size_t size() const { return positions.size(); }
    double totalArea() const;
    /// Whether every node has its normal (false once they were dropped or never loaded).
    bool hasNormals() const { return normals.size() == positions.size(); }
    /// Free the normals (not just empty them: the memory is what this is for).
    void dropNormals() { std::vector<Vec3>().swap(normals); }
};

/// Nodes at the vertices of @a mesh, areas by @a rule, normals angle-weighted from the faces.
/// Vertices no triangle uses are dropped.
SurfaceNodes nodesFromMesh(const TriangleMesh& mesh, AreaRule rule);

/// Reorder nodes along a Morton (Z-order) curve of cells of size @a cellSize, so neighbours in
/// the array are neighbours in space and level-set lookups stay cache-friendly.
void sortNodesSpatially(SurfaceNodes& nodes, double cellSize);

/// A run of consecutive items (in Morton order, so close together) and a sphere holding them:
/// the narrow phase skips a whole run when the sphere is clear of the other grain.
struct NodeBlock
{
    int begin = 0, end = 0;       ///< indices [begin, end) of nodes (a block) or blocks (a cluster)
    Vec3 center = Vec3::Zero();   ///< of the run's bounding sphere, asset frame
    double radius = 0.0;
};

/// The nodes grouped for culling, in two levels: blocks of a few consecutive nodes, and
/// clusters of consecutive blocks. A contact test skips a cluster clear of the other body
/// without looking at its blocks, and a block without looking at its nodes.
struct NodeBlocks
{
    std::vector<NodeBlock> blocks;    ///< begin/end: node indices, covering every node once
    std::vector<NodeBlock> clusters;  ///< begin/end: block indices, covering every block once

    bool empty() const { return blocks.empty(); }
    void clear()
    {
        blocks.clear();
        clusters.clear();
    }
    /// Whether they describe exactly @a nodeCount nodes (blocks made for other nodes would
    /// silently drop contacts).
    bool matches(size_t nodeCount) const
    {
        return !blocks.empty() && blocks.back().end == static_cast<int>(nodeCount) &&
               !clusters.empty() && clusters.back().end == static_cast<int>(blocks.size());
    }
};

/// Cut the (spatially sorted) nodes into blocks of at most @a blockSize nodes and the blocks
/// into clusters of at most @a clusterSize blocks, each with its bounding sphere.
NodeBlocks groupNodesIntoBlocks(const SurfaceNodes& nodes, int blockSize = 8,
                                int clusterSize = 8);

/// Spacing statistics: for each node, the distance to its nearest other node.
struct NodeSpacing
{
    double mean = 0.0, min = 0.0, max = 0.0;
};
NodeSpacing nodeSpacing(const SurfaceNodes& nodes);

} // namespace lsdem
