/// @file RestrictedVoronoi.h
/// @brief The Voronoi cells of points (seeds) restricted to a triangle mesh: each seed's share
///        of the surface is the part of the surface closer to it than to any other seed.
///
/// Each triangle is clipped, seed by seed, by the bisector planes between the seeds that can
/// own part of it, so the cells are exact polygons: their areas sum to the mesh's area (to
/// round-off), and a seed's area, centroid and mean normal are integrals over its cell, not
/// sample counts. Used to place surface nodes (Lloyd's relaxation towards a centroidal
/// Voronoi tessellation) and to give them their tributary areas. Closeness is Euclidean, so
/// a part of the surface thinner than the seeds' spacing can be owned by a seed on its other
/// side; restrictedVoronoiCells reports such cells (facingAway) instead of guessing.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <vector>

namespace lsdem {

struct RestrictedVoronoiCell
{
    double area = 0.0;              ///< length²
    Vec3 moment = Vec3::Zero();     ///< ∫ x dA over the cell (centroid = moment / area)
    Vec3 normalArea = Vec3::Zero(); ///< ∫ n dA over the cell, n the triangles' unit normals
    /// Area of the cell on triangles turned more than 120° from the seed's own: the other
    /// side of a part thinner than the seeds' spacing, owned across it. The seed's own
    /// triangle is the cell's triangle nearest to it (the one it lies on): neither the cell's
    /// mean normal (zero for a cell shared equally by a plate's two faces) nor the plane
    /// nearest the seed (a far facet's plane can pass through it) tells the sides apart.
    double facingAway = 0.0;
};

/// Whether restrictedVoronoiCells measures the cells' facingAway (a second pass over the
/// triangles that could hold such parts) or leaves it 0 (a relaxation step needs only the
/// cells' areas and centroids).
enum class CellSides { Measured, Skipped };

/// The cells of @a seeds on @a mesh (closed or not; triangles of zero area add nothing), in the
/// seeds' order. The same numbers on any thread count.
std::vector<RestrictedVoronoiCell> restrictedVoronoiCells(const TriangleMesh& mesh,
                                                          const std::vector<Vec3>& seeds,
                                                          CellSides sides = CellSides::Measured);

} // namespace lsdem
