#include "lsdem/mesh/MeshPseudoNormals.h"

#include "MeshEdgeUses.h"

#include "lsdem/core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

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
    // Each edge's two uses are adjacent once sorted; the use running from the lower vertex to
    // the higher and the one running back are the two triangles across it from each other.
    const std::vector<EdgeUse> uses = collectEdgeUses(mesh);
    auto edgeSlot = [&](const EdgeUse& use) {
        const auto& tri = tris[size_t(use.triangle)];
        const auto lo = uint32_t(use.key >> 32), hi = uint32_t(use.key & 0xffffffffu);
        for (int k = 0; k < 3; ++k) {
            const auto a = uint32_t(tri[k]), b = uint32_t(tri[(k + 1) % 3]);
            if (std::min(a, b) == lo && std::max(a, b) == hi) return k;
        }
        return 0;  // never reached: the use came from this triangle
    };
    for (size_t i = 0; i < uses.size();) {
        size_t j = i;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        if (j - i != 2 || uses[i].forward == uses[i + 1].forward) {
            const auto lo = uses[i].key >> 32, hi = uses[i].key & 0xffffffffu;
            throw Error("", "the edge between vertices " + std::to_string(lo) + " and " +
                                std::to_string(hi) + " is used by " + std::to_string(j - i) +
                                " triangle(s)" + (j - i == 2 ? " running the same way" : ""),
                        "the signed distance needs a closed, manifold, consistently oriented "
                        "mesh (lsdem's mesh validation makes one or says why not)");
        }
        mAcross[size_t(uses[i].triangle)][edgeSlot(uses[i])] = uses[i + 1].triangle;
        mAcross[size_t(uses[i + 1].triangle)][edgeSlot(uses[i + 1])] = uses[i].triangle;
        i = j;
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
    const auto& tri = mMesh.triangles[size_t(t)];
    TriangleFeature feature;
    const Vec3 offset = offsetFromTriangle(p, mMesh.vertices[size_t(tri[0])],
                                           mMesh.vertices[size_t(tri[1])],
                                           mMesh.vertices[size_t(tri[2])], feature);
    return offset.dot(pseudoNormal(t, feature)) > 0.0;
}

} // namespace lsdem
