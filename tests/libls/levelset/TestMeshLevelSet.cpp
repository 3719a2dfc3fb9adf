// Tests of meshLevelSet: the narrow band and the interior fill against the exact distance to
// the polyhedron (brute force over all triangles) and to the analytic shape it approximates.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/ls/MeshLevelSet.h"

#include "support/TestMeshes.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using lsdem::LevelSetGrid;
using lsdem::TriangleMesh;
using lsdem::Vec3;

namespace {

/// Distance from @a p to the segment [a, b].
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

/// Distance from @a p to a triangle: to its plane if the foot lies inside (barycentric
/// coordinates all non-negative), otherwise to the nearest of its edges.
double triangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 n = (b - a).cross(c - a);
    const Vec3 foot = p - (p - a).dot(n) / n.squaredNorm() * n;
    const double u = (b - foot).cross(c - foot).dot(n), v = (c - foot).cross(a - foot).dot(n),
                 w = (a - foot).cross(b - foot).dot(n);
    if (u >= 0 && v >= 0 && w >= 0) return (p - foot).norm();
    return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c),
                     segmentDistance(p, c, a)});
}

/// The exact unsigned distance from @a p to @a mesh: the nearest of all its triangles.
double bruteForceDistance(const TriangleMesh& mesh, const Vec3& p)
{
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles)
        best = std::min(best, triangleDistance(p, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                               mesh.vertices[t[2]]));
    return best;
}

Vec3 voxelCentre(const LevelSetGrid& ls, const openvdb::Coord& c)
{
    return ls.origin + ls.voxelSize * Vec3(c.x(), c.y(), c.z());
}

/// A non-convex closed surface: the level-3 icosphere (1280 triangles) with radial bumps of
/// ±18 %, so the interior has concave pockets where closest triangles change abruptly.
TriangleMesh bumpySphere()
{
    TriangleMesh mesh = lsdem::test::makeIcosphere(3);
    for (Vec3& v : mesh.vertices)
        v *= 1.0 + 0.12 * std::sin(3 * v.x()) * std::cos(3 * v.y()) + 0.06 * std::sin(4 * v.z());
    return mesh;
}

/// The narrow band (the exterior, and two voxels inside) is each voxel's distance to its
/// nearest triangle, in double: what is left is its rounding to a float and then to the
/// bricks, within 2^-10 + 2^-21·|largest| voxel on a plane brick and a whole step (2.0e-3
/// voxel) where that keeps the sign (LevelSetBricks.h). 2.1e-3 voxel is asserted. (OpenVDB's
/// band, used until 2026-11-30, was within 0.008 voxel here, computed in float index space.)
constexpr double kBandVoxels = 2.1e-3;
/// The interior fill takes each voxel's closest triangle among its 26 neighbours'. Where the
/// closest triangle changes abruptly (the medial axis, concave pockets) it can miss the true
/// one and take a slightly farther triangle: measured up to 0.05 voxel too deep on the bumpy
/// sphere, never too shallow (a distance to some triangle is never below the minimum over all).
/// 0.1 voxel is asserted: a tenth of the accuracy a voxel grid claims anyway.
constexpr double kFillVoxels = 0.1;

TEST(MeshLevelSet, InteriorFillIsTheExactDistanceToTheNearestTriangle)
{
    // Every voxel inside a non-convex mesh holds minus its distance to the mesh, as found by
    // brute force over all 1280 triangles, within the fill's tolerance (the deepest voxels
    // are 14 voxels in); the fill may only err deeper (a wrong triangle is farther), the
    // band either way.
    const TriangleMesh mesh = bumpySphere();
    const double vox = 0.06;
    for (const int band : {2, 3}) {
        SCOPED_TRACE("band " + std::to_string(band));
        const auto ls = lsdem::meshLevelSet(mesh, vox, band);
        size_t inside = 0;
        double deepest = 0.0;
        const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*ls->grid);
        for (auto it = stored->cbeginValueOn(); it; ++it) {
            ASSERT_TRUE(it.isVoxelValue()) << "the interior is stored voxel by voxel";
            if (*it >= 0.0f) continue;
            ++inside;
            const double depth = -double(*it);
            const double exact = bruteForceDistance(mesh, voxelCentre(*ls, it.getCoord()));
            deepest = std::max(deepest, exact);
            EXPECT_GE(depth, exact - kBandVoxels * vox) << it.getCoord();
            EXPECT_LE(depth, exact + kFillVoxels * vox) << it.getCoord();
        }
        EXPECT_GT(deepest, 10 * vox);
        // The volume of the inside voxels is the mesh's volume, within the voxels the surface
        // crosses (area × one voxel / 2 either way is generous): the interior is all filled.
        const double volume = lsdem::test::signedVolume(mesh);
        EXPECT_NEAR(double(inside) * vox * vox * vox, volume, 0.5 * 4 * M_PI * 1.3 * 1.3 * vox);
    }
}

TEST(MeshLevelSet, EveryVoxelInsideIsActiveAndNegativeAndTheBandIsExact)
{
    // A sphere mesh: every voxel centre within the mesh's inscribed radius is active and
    // negative; values in the exterior band are the exact distance to the polyhedron; and the
    // polyhedron is within its chord sagitta of the sphere, so φ is within that (plus round-off)
    // of the analytic sphere's distance at every active voxel.
    const TriangleMesh mesh = lsdem::test::makeIcosphere(4);  // 5120 triangles, edges ~0.08
    const double vox = 0.05;
    for (const int band : {2, 3}) {
        SCOPED_TRACE("band " + std::to_string(band));
        const auto ls = lsdem::meshLevelSet(mesh, vox, band);
        double rInscribed = 1.0;
        for (const auto& t : mesh.triangles) {
            const Vec3& a = mesh.vertices[t[0]];
            const Vec3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
            rInscribed = std::min(rInscribed, std::abs(n.dot(a)));
        }
        const double sagitta = 1.0 - rInscribed;
        ASSERT_LT(sagitta, 0.1 * vox);  // the test's premise: the mesh is a sphere to 0.1 voxel

        const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*ls->grid);
        auto accessor = stored->getConstAccessor();
        const int n = int(std::ceil((1.0 + 4 * vox) / vox)) + 4;
        const openvdb::Coord centre(int(std::lround(-ls->origin.x() / vox)),
                                    int(std::lround(-ls->origin.y() / vox)),
                                    int(std::lround(-ls->origin.z() / vox)));
        size_t checked = 0;
        for (int i = -n; i <= n; ++i)
            for (int j = -n; j <= n; ++j)
                for (int k = -n; k <= n; ++k) {
                    const openvdb::Coord c = centre.offsetBy(i, j, k);
                    const Vec3 p = voxelCentre(*ls, c);
                    if (p.norm() < rInscribed - 1e-9) {
                        ASSERT_TRUE(accessor.isValueOn(c)) << "inside voxel " << c << " not stored";
                        EXPECT_LT(accessor.getValue(c), 0.0f);
                    }
                    if (!accessor.isValueOn(c)) continue;
                    const double phi = accessor.getValue(c);
                    const double tolerance = (phi < -2 * vox ? kFillVoxels : kBandVoxels) * vox;
                    EXPECT_NEAR(phi, p.norm() - 1.0, sagitta + tolerance) << c;
                    if (phi > 0.0 && (++checked % 7 == 0)) {  // the exterior band, a sample of it
                        EXPECT_NEAR(phi, bruteForceDistance(mesh, p), kBandVoxels * vox) << c;
                    }
                }
        EXPECT_GT(checked, 1000u);  // exterior band voxels seen
    }
}

TEST(MeshLevelSet, BoxMeshGivesTheAnalyticBoxDistance)
{
    // A box mesh is the box exactly, so φ is the analytic box's signed distance at every
    // active voxel (the interior's medial planes are where propagated faces meet), and the
    // exterior band stops at its width.
    const Vec3 size(1.0, 0.6, 0.4);
    const TriangleMesh mesh = lsdem::test::makeBox(-0.5 * size, 0.5 * size);
    const auto box = lsdem::AnalyticShape::box(size.x(), size.y(), size.z());
    const double vox = 0.043;  // no voxel centre on a face, for either band's origin
    for (const int band : {2, 3}) {
        SCOPED_TRACE("band " + std::to_string(band));
        const auto ls = lsdem::meshLevelSet(mesh, vox, band);
        size_t inside = 0;
        const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*ls->grid);
        for (auto it = stored->cbeginValueOn(); it; ++it) {
            const Vec3 p = voxelCentre(*ls, it.getCoord());
            const double exact = box.signedDistance(p);
            EXPECT_NEAR(*it, exact, kBandVoxels * vox) << it.getCoord();
            EXPECT_LT(exact, (band + kBandVoxels) * vox);
            if (exact < 0) ++inside;
        }
        // Every voxel centre strictly inside: (cells along each axis within the half-extents).
        size_t expected = 1;
        for (int k = 0; k < 3; ++k) {
            const double lo = (-0.5 * size[k] - ls->origin[k]) / vox,
                         hi = (0.5 * size[k] - ls->origin[k]) / vox;
            expected *= size_t(std::ceil(hi) - std::floor(lo) - 1);
        }
        EXPECT_EQ(inside, expected);
    }
}

/// Signed distance from @a p to the box [lo, hi]: the analytic box's, moved there.
double boxSignedDistance(const Vec3& p, const Vec3& lo, const Vec3& hi)
{
    const Vec3 size = hi - lo;
    return lsdem::AnalyticShape::box(size.x(), size.y(), size.z()).signedDistance(p - 0.5 * (lo + hi));
}

TEST(MeshLevelSet, ABlockWithACavityAndARattlerHasEachVoxelOnItsSide)
{
    // Three closed parts: a block, a cavity in it (its surface facing inward) and a smaller
    // block inside the cavity. The surface is the three boxes' boundaries, so the exact
    // distance is the least of their |box distances|, negative in the block's shell and in
    // the rattler; the cavity around the rattler is outside (the background beyond the band).
    const Vec3 outerLo(0, 0, 0), outerHi(2, 2, 2), cavityLo(0.4, 0.4, 0.4), cavityHi(1.6, 1.6, 1.6),
        rattlerLo(0.8, 0.8, 0.8), rattlerHi(1.2, 1.2, 1.2);
    using lsdem::test::makeBox;
    const TriangleMesh mesh = lsdem::test::mergeWelded(
        lsdem::test::mergeWelded(makeBox(outerLo, outerHi),
                                 lsdem::test::reversed(makeBox(cavityLo, cavityHi))),
        makeBox(rattlerLo, rattlerHi));
    const double vox = 0.043;  // no voxel centre on a face
    const int band = 2;
    const auto ls = lsdem::meshLevelSet(mesh, vox, band);
    const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*ls->grid);
    auto accessor = stored->getConstAccessor();
    size_t shell = 0, rattler = 0, cavity = 0;
    const openvdb::CoordBBox table = ls->grid->tableBox();
    for (auto c = table.begin(); c; ++c) {
        const Vec3 p = voxelCentre(*ls, *c);
        const double dOuter = boxSignedDistance(p, outerLo, outerHi),
                     dCavity = boxSignedDistance(p, cavityLo, cavityHi),
                     dRattler = boxSignedDistance(p, rattlerLo, rattlerHi);
        const bool inside = (dOuter < 0 && dCavity > 0) || dRattler < 0;
        const double unsignedDistance =
            std::min({std::abs(dOuter), std::abs(dCavity), std::abs(dRattler)});
        const double exact = inside ? -unsignedDistance : unsignedDistance;
        if (exact >= band * vox) {
            ASSERT_FALSE(accessor.isValueOn(*c)) << *c;
            ASSERT_NEAR(accessor.getValue(*c), stored->background(), kBandVoxels * vox) << *c;
            continue;
        }
        ASSERT_TRUE(accessor.isValueOn(*c)) << *c;
        const double phi = accessor.getValue(*c);
        if (exact > -2 * vox) {  // the band
            ASSERT_NEAR(phi, exact, kBandVoxels * vox) << *c;
        } else {  // the fill: never too shallow
            ASSERT_LE(phi, exact + kBandVoxels * vox) << *c;
            ASSERT_GE(phi, exact - kFillVoxels * vox) << *c;
        }
        if (dRattler < 0) ++rattler;
        else if (inside) ++shell;
        else if (dCavity < 0) ++cavity;
    }
    EXPECT_GT(rattler, 500u);  // 9^3 voxel centres in the rattler
    EXPECT_GT(shell, 50000u);
    EXPECT_GT(cavity, 1000u);  // the cavity's band around the rattler and along its walls
}

TEST(MeshLevelSet, SameValuesOnAnyThreadCount)
{
    // The band's leaves, the fill's layers and the bricks are made in parallel; every value
    // and state comes out the same bits on one thread and on two. (Voxels fine enough that
    // the fill's layers are written by several tasks: 1.3 million voxels.)
    const TriangleMesh mesh = bumpySphere();
    auto bakeOn = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        return lsdem::meshLevelSet(mesh, 0.015, 3);
    };
    const auto one = bakeOn(1), two = bakeOn(2);
    ASSERT_EQ(one->grid->tableBox(), two->grid->tableBox());
    ASSERT_EQ(one->grid->memUsage(), two->grid->memUsage());
    size_t compared = 0;
    for (auto c = one->grid->tableBox().begin(); c; ++c) {
        const float a = one->grid->value(*c), b = two->grid->value(*c);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << *c;
        ASSERT_EQ(one->grid->isValueOn(*c), two->grid->isValueOn(*c)) << *c;
        ++compared;
    }
    EXPECT_GT(compared, 100000u);
}

TEST(MeshLevelSet, AnEightVoxelBlockNearHundredsOfTrianglesKeepsEachVoxelsNearest)
{
    // While it is baked, each 8³ block of voxels keeps the distinct codes of its voxels'
    // nearest triangles and, per voxel, an index into them of one byte, of two beyond 256
    // (ClosestTriangleGrid.h). A sphere of 81,920 triangles (edges about 0.014) in voxels of
    // 0.1 puts hundreds of distinct nearest triangles in one block by the surface (the test's
    // premise, counted by brute force); every band voxel of the block still holds its exact
    // distance, and every voxel deeper is filled.
    const TriangleMesh mesh = lsdem::test::makeIcosphere(6);
    const double vox = 0.1;
    const int band = 3;
    const auto ls = lsdem::meshLevelSet(mesh, vox, band);
    const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*ls->grid);
    auto accessor = stored->getConstAccessor();
    // The block holding the surface point along (1, 2, 3).
    const Vec3 onSurface = Vec3(1, 2, 3).normalized();
    openvdb::Coord first;
    for (int a = 0; a < 3; ++a)
        first[a] = int(std::lround((onSurface[a] - ls->origin[a]) / vox)) & ~7;
    std::vector<int> nearestInBand;
    size_t checked = 0;
    for (int n = 0; n < 512; ++n) {
        const openvdb::Coord c = first.offsetBy(n >> 6, (n >> 3) & 7, n & 7);
        const Vec3 p = voxelCentre(*ls, c);
        double best = std::numeric_limits<double>::infinity();
        int nearest = -1;
        for (size_t t = 0; t < mesh.triangles.size(); ++t) {
            const auto& tri = mesh.triangles[t];
            const double d = triangleDistance(p, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                              mesh.vertices[tri[2]]);
            if (d < best) best = d, nearest = int(t);
        }
        const double exact = p.norm() < 1.0 ? -best : best;  // (the sphere's inside)
        if (exact >= band * vox) {
            EXPECT_FALSE(accessor.isValueOn(c)) << c;  // beyond the exterior band
            continue;
        }
        ASSERT_TRUE(accessor.isValueOn(c)) << c;
        ++checked;
        if (exact < -2 * vox) {
            // The fill's voxels: inside, and never shallower than the nearest triangle. (With
            // triangles this much finer than the voxels, the fill's choice among its
            // neighbours' triangles errs deeper by up to 0.102 voxel here, past the coarser
            // meshes' kFillVoxels; the values are those of the Int32 tree's bake.)
            EXPECT_LT(accessor.getValue(c), 0.0f) << c;
            EXPECT_LE(accessor.getValue(c), exact + kBandVoxels * vox) << c;
            continue;
        }
        EXPECT_NEAR(accessor.getValue(c), exact, kBandVoxels * vox) << c;
        nearestInBand.push_back(nearest);
    }
    std::sort(nearestInBand.begin(), nearestInBand.end());
    const auto distinct = std::unique(nearestInBand.begin(), nearestInBand.end()) - nearestInBand.begin();
    ASSERT_GT(distinct, 256) << "the premise: more nearest triangles than one byte can index";
    EXPECT_GT(checked, 200u);
}

// Contact reads φ and ∇φ only in cells with a corner inside; their corners are inside or
// within √3 voxels of the surface. So a 2-voxel band samples as a 3-voxel one within half a
// voxel of the surface, to the bricks' rounding, which differs as the grids start at other
// voxels: each corner within 2.4e-7 of the float as 24 bits (docs/assets.md) and then within
// a plane brick's step (at most 2^-9 voxel), so φ within twice their sum and ∇φ within
// √3·4 times it per voxel (a missing corner would be off by 0.01 or more). Deeper, the fill
// reads the two grids' own voxels, and its choice of triangle can differ there, within its
// own error (kFillVoxels). A band of 1, which would miss corners of such
// cells, is refused.
TEST(MeshLevelSet, ATwoVoxelBandSamplesAsAThreeVoxelBandNearTheSurface)
{
    const TriangleMesh mesh = lsdem::test::makeIcosphere(4);
    const double vox = 0.05;
    const auto two = lsdem::meshLevelSet(mesh, vox, 2), three = lsdem::meshLevelSet(mesh, vox, 3);
    EXPECT_LT(two->grid->activeVoxelCount(), three->grid->activeVoxelCount());
    lsdem::LevelSetSampler a(*two), b(*three);
    std::mt19937_64 rng(4);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> depth(0.0, 0.3);
    int near = 0;
    for (int k = 0; k < 3000; ++k) {
        const double d = depth(rng);
        const Vec3 p = (0.995 - d) * Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const lsdem::LevelSetSample x = a.sample(p), y = b.sample(p);
        if (d < 0.5 * vox) {
            ++near;
            const double corner = 2.4e-7 + lsdem::LevelSetBricks::kNarrowPlaneStepVoxels * vox;
            ASSERT_NEAR(x.phi, y.phi, 2.0 * corner) << "at " << p.transpose();
            ASSERT_LT((x.gradient - y.gradient).norm(), std::sqrt(3.0) * 4.0 * corner / vox)
                << "at " << p.transpose();
        } else {
            ASSERT_NEAR(x.phi, y.phi, kFillVoxels * vox) << "at " << p.transpose();
        }
    }
    EXPECT_GT(near, 200);
    EXPECT_THROW(lsdem::meshLevelSet(mesh, vox, 1), lsdem::Error);
}

} // namespace
