/// @file CentroidalNodes.h
/// @brief Surface nodes placed on a triangle mesh without remeshing it: random points thinned
///        to an even spread (sample elimination), relaxed towards a centroidal Voronoi
///        tessellation of the surface (Lloyd's iteration on the restricted Voronoi cells), each
///        node given its cell's exact area and mean normal.
///
/// The cost grows with the input's triangles and the nodes, not with how far the input's
/// edges are from the node spacing, which is what makes remeshing slow on fine scans.
/// Sharp edges are not kept: a node sits where its cell's centroid is, so a shape whose
/// corners and edges matter (a block) is remeshed instead (countSharpEdges).
#pragma once

#include "lsdem/mesh/RestrictedVoronoi.h"
#include "lsdem/mesh/TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace lsdem {

struct CentroidalNodeOptions
{
    int candidatesPerNode = 5;   ///< random points drawn per node before thinning
    int lloydIterations = 3;     ///< relaxation steps towards the centroidal tessellation
    uint64_t seed = 1;           ///< of the random points (the same nodes for the same input)
};

struct CentroidalNodes
{
    std::vector<Vec3> positions;             ///< on the surface
    std::vector<RestrictedVoronoiCell> cells; ///< each node's cell at its final position
};

/// @a count nodes on @a mesh (closed, outward). Deterministic, the same on any thread count.
/// @throw Error for a mesh without area or a count below 4.
CentroidalNodes placeCentroidalNodes(const TriangleMesh& mesh, size_t count,
                                     const CentroidalNodeOptions& options = {});

/// How many edges of @a mesh join two triangles at a dihedral angle over @a angleDeg (their
/// normals turn by more than that across the edge).
size_t countSharpEdges(const TriangleMesh& mesh, double angleDeg);

} // namespace lsdem
