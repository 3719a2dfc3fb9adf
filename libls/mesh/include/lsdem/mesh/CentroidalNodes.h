/// @file CentroidalNodes.h
/// @brief Surface nodes placed on a triangle mesh without remeshing it: random points thinned
///        to an even spread (sample elimination), relaxed towards a centroidal Voronoi
///        tessellation of the surface (Lloyd's iteration on the restricted Voronoi cells), each
///        node given its cell's exact area and mean normal.
///
/// The cost grows with the input's triangles and the nodes, not with how far the input's
/// edges are from the node spacing, which is what makes remeshing slow on fine scans.
/// Sharp edges are not kept: a node sits where its cell's centroid is, so a shape whose
/// corners and edges matter (a block) is remeshed instead (countSharpEdges), unless its sharp
/// edges look like a scan's noise (sharpEdgesLookLikeNoise).
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

/// The sharp edges of a mesh: those joining two triangles at a dihedral angle over a limit.
struct SharpEdges
{
    size_t edges = 0;
    /// Vertices that exactly one sharp edge meets. A shape's edges run in lines that meet at
    /// its corners, with no loose end (a box's, however finely tessellated); a scan's noise
    /// turns edges sharp here and there, in short chains with two loose ends each.
    size_t looseEnds = 0;
};

/// The edges of @a mesh whose triangles' normals turn by more than @a angleDeg across them.
SharpEdges countSharpEdges(const TriangleMesh& mesh, double angleDeg);

/// From this many sharp edges on, a mesh's sharp edges are counted as noise by their loose
/// ends alone (fewer are noise only when each is alone), and the bake says what it made of
/// them.
inline constexpr size_t kManySharpEdges = 1000;

/// Whether sharp edges @a s look like a scan's noise rather than a shape's edges: each one on
/// its own (both of its ends loose), or a thousand and more with at least one loose end per 20
/// of them. A box's edges, however finely tessellated, have no loose end; the noisy meshes
/// measured had 0.09 to 1.3 per sharp edge (docs/assets.md).
bool sharpEdgesLookLikeNoise(const SharpEdges& s);

} // namespace lsdem
