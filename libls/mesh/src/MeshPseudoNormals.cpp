#include "lsdem/mesh/MeshPseudoNormals.h"

#include "lsdem/core/Error.h"

#include "VertexTriangles.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace lsdem {

MeshPseudoNormals::MeshPseudoNormals(const TriangleMesh& mesh)
    : mMesh(mesh), mCornerNormal(mesh.vertices.size(), Vec3::Zero()), mAcross(mesh.triangles.size())
{
    const auto& tris = mesh.triangles;
    for (int t = 0; t < int(tris.size()); ++t) {
        const Vec3 n = faceNormal(t);
        for (int k = 0; k < 3; ++k) {
            const Vec3& corner = mesh.vertices[size_t(tris[size_t(t)][k])];
            const Vec3 u = mesh.vertices[size_t(tris[size_t(t)][(k + 1) % 3])] - corner;
            const Vec3 v = mesh.vertices[size_t(tris[size_t(t)][(k + 2) % 3])] - corner;
            const double angle = std::atan2(u.cross(v).norm(), u.dot(v));
            mCornerNormal[size_t(tris[size_t(t)][k])] += angle * n;
        }
    }
    // The triangle across each edge: the edge a → b of one triangle must be the edge b → a
    // of exactly one other, and of no third.
    const VertexTriangles aroundVertex(mesh);
    // The triangles around @a a running along a → b, counted, and the last of them.
    auto runningAlong = [&](int a, int b, int32_t& found) {
        int count = 0;
        aroundVertex.forEachAround(a, [&](int t) {
            const auto& tri = tris[size_t(t)];
            for (int k = 0; k < 3; ++k)
                if (tri[k] == a && tri[(k + 1) % 3] == b) {
                    ++count;
                    found = t;
                }
        });
        return count;
    };
    for (int t = 0; t < int(tris.size()); ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = tris[size_t(t)][k], b = tris[size_t(t)][(k + 1) % 3];
            int32_t same = -1, across = -1;
            const int forward = runningAlong(a, b, same), backward = runningAlong(b, a, across);
            if (forward != 1 || backward != 1) {
                const int uses = forward + backward;
                throw Error("", "the edge between vertices " + std::to_string(std::min(a, b)) +
                                    " and " + std::to_string(std::max(a, b)) + " is used by " +
                                    std::to_string(uses) + " triangle(s)" +
                                    (uses == 2 ? " running the same way" : ""),
                            "the signed distance needs a closed, manifold, consistently "
                            "oriented mesh (lsdem's mesh validation makes one or says why not)");
            }
            mAcross[size_t(t)][k] = across;
        }
}

Vec3 MeshPseudoNormals::faceNormal(int t) const
{
    const auto& tri = mMesh.triangles[size_t(t)];
    const Vec3& a = mMesh.vertices[size_t(tri[0])];
    return (mMesh.vertices[size_t(tri[1])] - a).cross(mMesh.vertices[size_t(tri[2])] - a).normalized();
}

Vec3 MeshPseudoNormals::pseudoNormal(int t, TriangleFeature feature) const
{
    const auto& tri = mMesh.triangles[size_t(t)];
    switch (feature) {
    case TriangleFeature::EdgeAB: return faceNormal(t) + faceNormal(mAcross[size_t(t)][0]);
    case TriangleFeature::EdgeBC: return faceNormal(t) + faceNormal(mAcross[size_t(t)][1]);
    case TriangleFeature::EdgeCA: return faceNormal(t) + faceNormal(mAcross[size_t(t)][2]);
    case TriangleFeature::CornerA: return mCornerNormal[size_t(tri[0])];
    case TriangleFeature::CornerB: return mCornerNormal[size_t(tri[1])];
    case TriangleFeature::CornerC: return mCornerNormal[size_t(tri[2])];
    case TriangleFeature::Face: break;
    }
    return faceNormal(t);
}

bool MeshPseudoNormals::isOutside(const Vec3& p, int t) const
{
    TriangleFeature feature;
    const Vec3 offset = offsetFromTriangle(p, mMesh, t, feature);
    return offset.dot(pseudoNormal(t, feature)) > 0.0;
}

} // namespace lsdem
