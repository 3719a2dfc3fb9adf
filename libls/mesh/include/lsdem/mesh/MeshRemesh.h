/// @file MeshRemesh.h
/// @brief Isotropic remeshing of a closed triangle mesh to a target edge length (CGAL
///        Polygon_mesh_processing), keeping sharp feature edges (box edges, block edges).
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

namespace lsdem {

struct RemeshOptions
{
    double targetEdgeLength = 0.0;  ///< wanted mean edge length (the SDP), > 0
    double featureAngleDeg = 30.0;  ///< dihedral angle above which an edge is a sharp feature
    int iterations = 5;             ///< CGAL remeshing iterations
    /// Remesh an input whose mean edge is below about 0.77 of the target nearly as it is
    /// (only its edges longer than that are split), instead of refining it to 0.44 of the
    /// target first: about 5x faster on a 100k-triangle scan, with a mean edge up to about
    /// 4 % further from the target (the result then depends a little on the input's edges).
    bool keepFineInput = false;
};

/// Remesh @a input (closed, consistently oriented) so its edges are about
/// options.targetEdgeLength long. Sharp edges stay sharp, corners stay put. The input is first
/// refined by midpoint splits so the result does not depend on its resolution (but see
/// keepFineInput); the mean edge
/// of the result is within about 3 % of the target. Cost: about 0.3 s for 2,000 nodes and
/// 30 s for 100,000 on one core.
/// @throw Error if CGAL rejects the mesh or the result is not a closed mesh.
TriangleMesh remeshIsotropic(const TriangleMesh& input, const RemeshOptions& options);

/// The edge length that gives about @a nodeCount vertices on a surface of area @a area with
/// near-equilateral triangles (each vertex owns two triangles of area sqrt(3)/4 h^2).
double edgeLengthForNodeCount(double area, int nodeCount);

/// Its inverse: about how many vertices near-equilateral triangles of edge @a edgeLength
/// place on a surface of area @a area, 2A/(√3·h²) (what a node spacing, the SDP, asks for).
double nodeCountForEdgeLength(double area, double edgeLength);

} // namespace lsdem
