/// @file MeshPseudoNormals.h
/// @brief Which side of a closed mesh a point lies on, from the triangle nearest to it: the
///        angle-weighted pseudo-normal of the part of that triangle (inside, edge or corner)
///        that holds the closest point (Bærentzen & Aanæs, IEEE TVCG 11(3), 2005).
#pragma once

#include "lsdem/mesh/TriangleMesh.h"
#include "lsdem/mesh/TriangleOffset.h"

#include <array>
#include <cstdint>
#include <vector>

namespace lsdem {

/// For a closed, manifold, consistently oriented (outward) mesh, the sign of a point's
/// distance from its nearest triangle alone: the offset from the closest point has a positive
/// dot product with the pseudo-normal of the feature holding it exactly when the point is
/// outside. The pseudo-normals are the face's normal inside a triangle, the sum of the two
/// faces' unit normals on an edge, and the sum of the incident faces' unit normals weighted
/// by their angles at a corner. Holds @a mesh by reference.
class MeshPseudoNormals
{
public:
    /// Throws lsdem::Error if an edge is not shared by exactly two triangles running along it
    /// in opposite directions (an open, non-manifold or inconsistently oriented mesh).
    explicit MeshPseudoNormals(const TriangleMesh& mesh);

    /// Whether @a p lies outside the mesh, triangle @a t being nearest to it (any of the
    /// nearest, if several are). A point on the surface may be called either.
    bool isOutside(const Vec3& p, int t) const;

private:
    /// Triangle @a t's unit normal.
    Vec3 faceNormal(int t) const;
    /// The pseudo-normal of @a feature of triangle @a t.
    Vec3 pseudoNormal(int t, TriangleFeature feature) const;

    const TriangleMesh& mMesh;
    std::vector<Vec3> mCornerNormal;  ///< per vertex: the angle-weighted sum
    /// Per triangle, the triangle across each edge: [k] across the edge from corner k to k + 1.
    std::vector<std::array<int32_t, 3>> mAcross;
};

} // namespace lsdem
