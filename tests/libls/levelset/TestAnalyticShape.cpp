// Analytic shapes: exact distances, areas and mass properties against closed forms.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/core/Error.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace lsdem;
using lsdem::kPi;

TEST(AnalyticShape, SphereAndBoxDistancesMatchClosedForms)
{
    const AnalyticShape s = AnalyticShape::sphere(2.0);
    EXPECT_DOUBLE_EQ(s.signedDistance(Vec3(0, 0, 0)), -2.0);
    EXPECT_DOUBLE_EQ(s.signedDistance(Vec3(3, 4, 0)), 3.0);
    const AnalyticShape b = AnalyticShape::box(2.0, 4.0, 6.0);  // half extents 1, 2, 3
    EXPECT_DOUBLE_EQ(b.signedDistance(Vec3(0, 0, 0)), -1.0);      // nearest face x = ±1
    EXPECT_DOUBLE_EQ(b.signedDistance(Vec3(0, 0, 3.5)), 0.5);     // above a face
    EXPECT_DOUBLE_EQ(b.signedDistance(Vec3(2, 3, 3)), std::sqrt(2.0));  // beyond an edge
    EXPECT_DOUBLE_EQ(b.signedDistance(Vec3(4, 6, 7)), std::sqrt(9.0 + 16 + 16));  // corner
}

// The ellipsoid distance is exact if the closest point x lies on the surface, p - x is along
// the surface normal at x, and no other surface point is closer (checked by sampling).
TEST(AnalyticShape, EllipsoidDistanceIsTheTrueMinimum)
{
    const AnalyticShape e = AnalyticShape::ellipsoid(3.0, 2.0, 1.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-4.0, 4.0);
    std::vector<Vec3> surface;
    for (int i = 0; i < 20000; ++i) {
        const double u = std::uniform_real_distribution<double>(-1, 1)(rng);
        const double phi = std::uniform_real_distribution<double>(0, 2 * kPi)(rng);
        const double r = std::sqrt(1 - u * u);
        surface.emplace_back(3.0 * r * std::cos(phi), 2.0 * r * std::sin(phi), 1.0 * u);
    }
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 p(uni(rng), uni(rng), uni(rng) * 0.5);
        const Vec3 x = e.closestSurfacePoint(p);
        EXPECT_NEAR((x.x() * x.x()) / 9 + (x.y() * x.y()) / 4 + x.z() * x.z(), 1.0, 1e-12);
        const Vec3 n = e.outwardNormal(x);
        const Vec3 d = p - x;
        if (d.norm() > 1e-9) {
            EXPECT_NEAR(std::abs(d.normalized().dot(n)), 1.0, 1e-9);
        }
        double sampled = 1e300;
        for (const Vec3& q : surface) sampled = std::min(sampled, (q - p).norm());
        const double exact = std::abs(e.signedDistance(p));
        EXPECT_LE(exact, sampled + 1e-12);
        EXPECT_NEAR(exact, sampled, 0.05);  // the samples are ~0.05 apart
        const bool inside = (p.x() * p.x()) / 9 + (p.y() * p.y()) / 4 + p.z() * p.z() < 1;
        EXPECT_EQ(e.signedDistance(p) < 0, inside);
    }
}

TEST(AnalyticShape, EllipsoidDistanceOnTheSymmetryPlanesIsContinuous)
{
    // Points on the axes (zero coordinates) are the hard case of the root finding.
    const AnalyticShape e = AnalyticShape::ellipsoid(3.0, 2.0, 1.0);
    EXPECT_NEAR(e.signedDistance(Vec3(0, 0, 0)), -1.0, 1e-9);
    EXPECT_NEAR(e.signedDistance(Vec3(5, 0, 0)), 2.0, 1e-9);
    EXPECT_NEAR(e.signedDistance(Vec3(0, 0, 2)), 1.0, 1e-9);
    EXPECT_NEAR(e.signedDistance(Vec3(1e-13, 1e-13, 0.5)), -0.5, 1e-9);
}

TEST(AnalyticShape, AreasAndMassPropertiesMatchClosedForms)
{
    const AnalyticShape s = AnalyticShape::sphere(5.0);
    EXPECT_NEAR(s.surfaceArea(), 4 * kPi * 25, 1e-9);
    EXPECT_NEAR(s.massProperties().volume, 4.0 / 3.0 * kPi * 125, 1e-9);
    EXPECT_NEAR(s.massProperties().inertia(1, 1), 0.4 * (4.0 / 3.0 * kPi * 125) * 25, 1e-9);

    const AnalyticShape b = AnalyticShape::box(1.0, 2.0, 3.0);
    EXPECT_DOUBLE_EQ(b.surfaceArea(), 22.0);
    EXPECT_DOUBLE_EQ(b.massProperties().volume, 6.0);
    EXPECT_NEAR(b.massProperties().inertia(0, 0), 6.0 / 12.0 * (4 + 9), 1e-12);

    // Ellipsoid area by Legendre's closed form with incomplete elliptic integrals (a > b > c).
    const double a = 3.0, bb = 2.0, c = 1.0;
    const double phi = std::acos(c / a);
    const double k = std::sqrt(a * a * (bb * bb - c * c) / (bb * bb * (a * a - c * c)));
    const double legendre = 2 * kPi * c * c +
                            2 * kPi * a * bb / std::sin(phi) *
                                (std::ellint_2(k, phi) * std::sin(phi) * std::sin(phi) +
                                 std::ellint_1(k, phi) * std::cos(phi) * std::cos(phi));
    const AnalyticShape e = AnalyticShape::ellipsoid(a, bb, c);
    EXPECT_NEAR(e.surfaceArea(), legendre, 1e-10 * legendre);
    const double volume = 4.0 / 3.0 * kPi * a * bb * c;
    EXPECT_NEAR(e.massProperties().inertia(2, 2), volume / 5 * (a * a + bb * bb), 1e-9);
}

TEST(AnalyticShape, SurfaceMeshesAreClosedAndOnTheSurface)
{
    for (const AnalyticShape& shape : {AnalyticShape::sphere(1.0), AnalyticShape::box(1, 2, 3),
                                       AnalyticShape::ellipsoid(2, 1, 0.5)}) {
        const TriangleMesh mesh = shape.surfaceMesh(0.2);
        // Closed orientable surface of genus 0: V - E + F = 2 with E = 3F/2.
        EXPECT_EQ(int(mesh.vertices.size()) - int(mesh.triangles.size()) / 2, 2);
        for (const Vec3& v : mesh.vertices) EXPECT_NEAR(shape.signedDistance(v), 0.0, 1e-9);
    }
}

TEST(AnalyticShape, RejectsNonPositiveSizes)
{
    EXPECT_THROW(AnalyticShape::sphere(0.0), Error);
    EXPECT_THROW(AnalyticShape::box(1, -1, 1), Error);
    EXPECT_THROW(AnalyticShape::ellipsoid(1, 1, std::nan("")), Error);
}

// The exact distance a level set may carry (ExactDistance.h): φ is the shape's signed distance,
// and the gradient is unit, points outwards on both sides, and matches φ's central differences
// away from the ridges (a box's medial planes, where φ has a kink).
TEST(AnalyticShape, ExactDistanceGradientIsUnitOutwardAndMatchesDifferences)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (const AnalyticShape& shape : {AnalyticShape::sphere(1.0), AnalyticShape::box(2.0, 1.6, 1.2),
                                       AnalyticShape::ellipsoid(1.0, 0.7, 0.5)}) {
        const auto exact = shape.exactDistance();
        int checked = 0;
        for (int k = 0; k < 400; ++k) {
            const Vec3 p(u(rng), u(rng), u(rng));
            EXPECT_EQ(exact->phi(p), shape.signedDistance(p));
            const Vec3 g = exact->gradient(p);
            EXPECT_NEAR(g.norm(), 1.0, 1e-9) << shape.describe();
            // Outwards: a small step along it raises φ.
            EXPECT_GT(exact->phi(p + 1e-4 * g), exact->phi(p)) << shape.describe();
            const double h = 1e-6;
            Vec3 difference;
            for (int axis = 0; axis < 3; ++axis) {
                const Vec3 e = Vec3::Unit(axis) * h;
                difference[axis] = (exact->phi(p + e) - exact->phi(p - e)) / (2.0 * h);
            }
            if (std::abs(difference.norm() - 1.0) > 1e-4) continue;  // on a ridge: no gradient
            EXPECT_LT((difference - g).norm(), 1e-4) << shape.describe() << " at " << p.transpose();
            ++checked;
        }
        EXPECT_GT(checked, 300) << shape.describe();
    }
}
