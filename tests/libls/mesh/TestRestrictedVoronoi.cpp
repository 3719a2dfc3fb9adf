// Tests of restrictedVoronoiCells: exact cells on a plane, areas against a brute-force
// nearest-seed count on a sphere, the whole surface shared out, a thin part owned across, and
// the same numbers on one thread or several.
#include "lsdem/mesh/RestrictedVoronoi.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

using lsdem::RestrictedVoronoiCell;
using lsdem::TriangleMesh;
using lsdem::Vec3;
using lsdem::restrictedVoronoiCells;

namespace {

/// The unit square in the plane z = 0, as two triangles facing +z.
TriangleMesh unitSquare()
{
    TriangleMesh mesh;
    mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

/// @a count points on the unit sphere, uniformly at random (fixed seed).
std::vector<Vec3> randomDirections(int count, unsigned seed)
{
    std::mt19937 random(seed);
    std::normal_distribution<double> normal;
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.push_back(Vec3(normal(random), normal(random), normal(random)).normalized());
    return points;
}

TEST(RestrictedVoronoi, SeedsAtTheCentresOfAGridOwnTheirSquares)
{
    // Seeds at the centres of a 4×4 grid of squares: each square is exactly one cell, whose
    // area is 1/16, whose centroid is its seed and whose normal is the plane's.
    std::vector<Vec3> seeds;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) seeds.emplace_back((i + 0.5) / 4, (j + 0.5) / 4, 0.0);
    const std::vector<RestrictedVoronoiCell> cells = restrictedVoronoiCells(unitSquare(), seeds);
    ASSERT_EQ(cells.size(), seeds.size());
    for (size_t s = 0; s < seeds.size(); ++s) {
        EXPECT_NEAR(cells[s].area, 1.0 / 16, 1e-15) << s;
        EXPECT_LT((cells[s].moment / cells[s].area - seeds[s]).norm(), 1e-14) << s;
        EXPECT_LT((cells[s].normalArea / cells[s].area - Vec3::UnitZ()).norm(), 1e-14) << s;
        EXPECT_EQ(cells[s].facingAway, 0.0);
    }
}

/// The cells of @a seedCount random seeds on an icosphere of @a levels subdivisions against a
/// brute-force count of a million points' nearest seeds.
void expectCellsMatchABruteForceCount(int levels, int seedCount)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(levels);
    const std::vector<Vec3> seeds = randomDirections(seedCount, 7);
    const std::vector<RestrictedVoronoiCell> cells = restrictedVoronoiCells(sphere, seeds);

    // The reference: a million points spread uniformly over the mesh's triangles, each given
    // to its nearest seed by checking every seed. A cell gets about a million / seedCount
    // points; its count's standard error is its square root.
    std::vector<double> triangleAreas;
    double total = 0.0;
    for (int t = 0; t < int(sphere.triangles.size()); ++t) {
        triangleAreas.push_back(lsdem::triangleArea(sphere, t));
        total += triangleAreas.back();
    }
    std::discrete_distribution<int> pickTriangle(triangleAreas.begin(), triangleAreas.end());
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::mt19937 random(11);
    const int samples = 1000000;
    std::vector<double> counted(seeds.size(), 0.0);
    for (int n = 0; n < samples; ++n) {
        const auto& tri = sphere.triangles[size_t(pickTriangle(random))];
        const double r1 = std::sqrt(unit(random)), r2 = unit(random);
        const Vec3 p = (1 - r1) * sphere.vertices[size_t(tri[0])] +
                       r1 * (1 - r2) * sphere.vertices[size_t(tri[1])] +
                       r1 * r2 * sphere.vertices[size_t(tri[2])];
        size_t nearest = 0;
        for (size_t s = 1; s < seeds.size(); ++s)
            if ((seeds[s] - p).squaredNorm() < (seeds[nearest] - p).squaredNorm()) nearest = s;
        counted[nearest] += 1.0;
    }
    double sum = 0.0;
    for (size_t s = 0; s < seeds.size(); ++s) {
        const double expected = counted[s] / samples * total;
        // Four standard errors of the count.
        EXPECT_NEAR(cells[s].area, expected, 4.0 * std::sqrt(counted[s]) / samples * total) << s;
        sum += cells[s].area;
        // Every cell is a patch of the sphere round its seed: its mean normal points along it.
        EXPECT_GT(cells[s].normalArea.normalized().dot(seeds[s]), 0.9) << s;
    }
    EXPECT_NEAR(sum, total, 1e-12 * total);  // the cells share out the whole surface
}

TEST(RestrictedVoronoi, CellsOnASphereMatchABruteForceCountOfNearestSeeds)
{
    expectCellsMatchABruteForceCount(4, 40);  // 5120 triangles, many to a cell
}

// Triangles larger than two cells are split before clipping (so a coarse mesh holding many
// seeds costs as many clips as a fine one): the cells are the same polygons.
TEST(RestrictedVoronoi, ACoarseMeshHoldingManySeedsGivesTheSameCells)
{
    expectCellsMatchABruteForceCount(1, 200);  // 80 triangles of 2.5 cells each: split
}

TEST(RestrictedVoronoi, APartThinnerThanTheSpacingIsOwnedAcrossAndReported)
{
    // A plate 1 × 1 × 0.02 with seeds on its top face only: the bottom face is nearer to the
    // top's seeds than to any other, so their cells reach through and face away.
    const TriangleMesh plate = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 0.02));
    std::vector<Vec3> seeds;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) seeds.emplace_back((i + 0.5) / 5, (j + 0.5) / 5, 0.02);
    double facingAway = 0.0;
    for (const RestrictedVoronoiCell& cell : restrictedVoronoiCells(plate, seeds))
        facingAway += cell.facingAway;
    EXPECT_NEAR(facingAway, 1.0, 1e-12);  // the whole bottom face

    // With seeds on both faces, nothing is owned across.
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) seeds.emplace_back((i + 0.5) / 5, (j + 0.5) / 5, 0.0);
    facingAway = 0.0;
    for (const RestrictedVoronoiCell& cell : restrictedVoronoiCells(plate, seeds))
        facingAway += cell.facingAway;
    EXPECT_EQ(facingAway, 0.0);
}

// A relaxation step asks for the cells without their sides: the same areas, centroids and
// normals to the bit, and facingAway left 0 (the plate above, owned across).
TEST(RestrictedVoronoi, CellsWithoutTheirSidesAreTheSameCells)
{
    const TriangleMesh plate = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 0.02));
    std::vector<Vec3> seeds;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) seeds.emplace_back((i + 0.5) / 5, (j + 0.5) / 5, 0.02);
    const auto measured = restrictedVoronoiCells(plate, seeds);
    const auto skipped = restrictedVoronoiCells(plate, seeds, lsdem::CellSides::Skipped);
    double facingAway = 0.0;
    for (size_t s = 0; s < seeds.size(); ++s) {
        EXPECT_EQ(skipped[s].area, measured[s].area) << s;
        EXPECT_EQ(skipped[s].moment, measured[s].moment) << s;
        EXPECT_EQ(skipped[s].normalArea, measured[s].normalArea) << s;
        EXPECT_EQ(skipped[s].facingAway, 0.0) << s;
        facingAway += measured[s].facingAway;
    }
    EXPECT_NEAR(facingAway, 1.0, 1e-12);
}

TEST(RestrictedVoronoi, GiveTheSameBitsOnOneThreadAsOnSeveral)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(5);
    const std::vector<Vec3> seeds = randomDirections(3000, 3);
    std::vector<RestrictedVoronoiCell> single;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        single = restrictedVoronoiCells(sphere, seeds);
    }
    const std::vector<RestrictedVoronoiCell> several = restrictedVoronoiCells(sphere, seeds);
    for (size_t s = 0; s < seeds.size(); ++s) {
        EXPECT_EQ(single[s].area, several[s].area) << s;
        EXPECT_EQ(single[s].moment, several[s].moment) << s;
        EXPECT_EQ(single[s].normalArea, several[s].normalArea) << s;
        EXPECT_EQ(single[s].facingAway, several[s].facingAway) << s;
    }
}

} // namespace
