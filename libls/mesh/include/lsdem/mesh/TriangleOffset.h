/// @file TriangleOffset.h
/// @brief The vector from the closest point of a triangle to a point: its length is the
///        distance, and the point minus it is the closest point.
#pragma once

#include "lsdem/core/Vec3.h"
#include "lsdem/mesh/TriangleMesh.h"

namespace lsdem {

/// Which part of a triangle (a, b, c) holds the point closest to a given point: its inside,
/// one of its edges, or one of its corners.
enum class TriangleFeature { Face, EdgeAB, EdgeBC, EdgeCA, CornerA, CornerB, CornerC };

/// p − q, q the point of triangle (a, b, c) closest to @a p, and in @a feature the part of the
/// triangle q lies on: found by which of the triangle's seven regions (three corners, three
/// edges, the inside) p projects into, from the signs of dot products of the edges with p's
/// offsets from the corners (Ericson, Real-Time Collision Detection, 5.1.5). Inline: the
/// interior fill calls it tens of millions of times per bake (through the overload below, so
/// the feature's stores vanish there).
inline Vec3 offsetFromTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                               TriangleFeature& feature)
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        feature = TriangleFeature::CornerA;
        return ap;
    }
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) {
        feature = TriangleFeature::CornerB;
        return bp;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        feature = TriangleFeature::EdgeAB;
        return ap - d1 / (d1 - d3) * ab;
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) {
        feature = TriangleFeature::CornerC;
        return cp;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        feature = TriangleFeature::EdgeCA;
        return ap - d2 / (d2 - d6) * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        feature = TriangleFeature::EdgeBC;
        return bp - (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    }
    feature = TriangleFeature::Face;
    const double denom = 1.0 / (va + vb + vc);  // inside: barycentric (1 − v − w, v, w)
    return ap - (vb * denom) * ab - (vc * denom) * ac;
}

/// p − q, q the point of triangle (a, b, c) closest to @a p.
inline Vec3 offsetFromTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    TriangleFeature unused;
    return offsetFromTriangle(p, a, b, c, unused);
}

/// The same for triangle @a t of @a mesh, and the part of it holding the closest point.
inline Vec3 offsetFromTriangle(const Vec3& p, const TriangleMesh& mesh, int t,
                               TriangleFeature& feature)
{
    const auto& tri = mesh.triangles[size_t(t)];
    return offsetFromTriangle(p, mesh.vertices[size_t(tri[0])], mesh.vertices[size_t(tri[1])],
                              mesh.vertices[size_t(tri[2])], feature);
}

/// The same for triangle @a t of @a mesh.
inline Vec3 offsetFromTriangle(const Vec3& p, const TriangleMesh& mesh, int t)
{
    TriangleFeature unused;
    return offsetFromTriangle(p, mesh, t, unused);
}

} // namespace lsdem
