// The side of a point from its nearest triangle's pseudo-normal, against the winding number
// (the solid angle the closed surface subtends, over 4π: 1 inside, 0 outside), which needs no
// normals at all.

#include "lsdem/core/Error.h"
#include "lsdem/mesh/MeshPseudoNormals.h"
#include "lsdem/mesh/TriangleOffset.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>

namespace {

using lsdem::TriangleFeature;
using lsdem::TriangleMesh;
using lsdem::Vec3;

/// The winding number of @a mesh about @a p: the triangles' signed solid angles (Van Oosterom
/// & Strackee, IEEE TBME 30(2), 1983) summed, over 4π.
double windingNumber(const TriangleMesh& mesh, const Vec3& p)
{
    double sum = 0.0;
    for (const auto& t : mesh.triangles) {
        const Vec3 a = mesh.vertices[size_t(t[0])] - p, b = mesh.vertices[size_t(t[1])] - p,
                   c = mesh.vertices[size_t(t[2])] - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double num = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4.0 * M_PI);
}

/// The nearest triangle to @a p (the lowest-numbered of equally near ones), its distance and
/// the feature holding the closest point.
struct Nearest
{
    int triangle = -1;
    double distance = std::numeric_limits<double>::infinity();
    TriangleFeature feature = TriangleFeature::Face;
};

Nearest nearestTriangle(const TriangleMesh& mesh, const Vec3& p)
{
    Nearest best;
    for (int t = 0; t < int(mesh.triangles.size()); ++t) {
        const auto& tri = mesh.triangles[size_t(t)];
        TriangleFeature feature;
        const double d = lsdem::offsetFromTriangle(p, mesh.vertices[size_t(tri[0])],
                                                   mesh.vertices[size_t(tri[1])],
                                                   mesh.vertices[size_t(tri[2])], feature)
                             .norm();
        if (d < best.distance) best = {t, d, feature};
    }
    return best;
}

/// A non-convex closed surface: a level-3 icosphere with radial bumps of about ±25 %.
TriangleMesh bumpySphere()
{
    TriangleMesh mesh = lsdem::test::makeIcosphere(3);
    for (Vec3& v : mesh.vertices)
        v *= 1.0 + 0.18 * std::sin(3 * v.x()) * std::cos(3 * v.y()) + 0.08 * std::sin(4 * v.z());
    return mesh;
}

/// A block with a cavity and a smaller block inside it (a rattler): three closed parts, one
/// of them facing inward; sharp convex and concave edges and corners.
TriangleMesh nestedBlocks()
{
    using lsdem::test::makeBox;
    return lsdem::test::mergeWelded(
        lsdem::test::mergeWelded(makeBox(Vec3(0, 0, 0), Vec3(5, 5, 5)),
                                 lsdem::test::reversed(makeBox(Vec3(1, 1, 1), Vec3(4, 4, 4)))),
        makeBox(Vec3(2, 2, 2), Vec3(3, 3, 3)));
}

TEST(MeshPseudoNormals, SideAgreesWithTheWindingNumberNearAndFar)
{
    // Points near the surface (a random point of a random triangle, moved by up to 0.3 of the
    // mesh's size in a random direction) and anywhere in its widened box; the closest points
    // fall on faces, edges and corners alike, and each kind is checked.
    for (const auto& [name, mesh] : {std::pair<std::string, TriangleMesh>{"bumpy", bumpySphere()},
                                     {"nested", nestedBlocks()}}) {
        SCOPED_TRACE(name);
        const lsdem::MeshPseudoNormals sides(mesh);
        const auto bounds = lsdem::meshBounds(mesh);
        const double size = (bounds[1] - bounds[0]).maxCoeff();
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::normal_distribution<double> gauss;
        std::map<TriangleFeature, int> seen;
        int inside = 0, outside = 0;
        for (int k = 0; k < 4000; ++k) {
            Vec3 p;
            if (k % 2 == 0) {
                const auto& t = mesh.triangles[size_t(rng() % mesh.triangles.size())];
                double u = unit(rng), v = unit(rng);
                if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                const Vec3 onSurface = mesh.vertices[size_t(t[0])] +
                                       u * (mesh.vertices[size_t(t[1])] - mesh.vertices[size_t(t[0])]) +
                                       v * (mesh.vertices[size_t(t[2])] - mesh.vertices[size_t(t[0])]);
                const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
                p = onSurface + 0.3 * size * std::pow(unit(rng), 3.0) * direction;
            } else {
                for (int a = 0; a < 3; ++a)
                    p[a] = bounds[0][a] - 0.2 * size + 1.4 * size * unit(rng);
            }
            const Nearest nearest = nearestTriangle(mesh, p);
            if (nearest.distance < 1e-6 * size) continue;  // on the surface: either side
            const double w = windingNumber(mesh, p);
            ASSERT_LT(std::min(std::abs(w), std::abs(w - 1.0)), 1e-6) << p.transpose();
            const bool outsideByWinding = w < 0.5;
            ASSERT_EQ(sides.isOutside(p, nearest.triangle), outsideByWinding)
                << "at " << p.transpose() << ", nearest triangle " << nearest.triangle
                << ", feature " << int(nearest.feature);
            ++seen[nearest.feature];
            (outsideByWinding ? outside : inside) += 1;
        }
        EXPECT_GT(inside, 300);
        EXPECT_GT(outside, 300);
        int edges = 0, corners = 0;
        for (const auto& [feature, count] : seen) {
            if (feature == TriangleFeature::EdgeAB || feature == TriangleFeature::EdgeBC ||
                feature == TriangleFeature::EdgeCA)
                edges += count;
            else if (feature != TriangleFeature::Face)
                corners += count;
        }
        EXPECT_GT(seen[TriangleFeature::Face], 300);
        EXPECT_GT(edges, 100);
        EXPECT_GT(corners, 50);
    }
}

TEST(MeshPseudoNormals, RefusesAnOpenOrInconsistentlyOrientedMesh)
{
    TriangleMesh open = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    open.triangles.pop_back();
    EXPECT_THROW(lsdem::MeshPseudoNormals{open}, lsdem::Error);
    TriangleMesh turned = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    std::swap(turned.triangles[2][1], turned.triangles[2][2]);
    EXPECT_THROW(lsdem::MeshPseudoNormals{turned}, lsdem::Error);
}

} // namespace
