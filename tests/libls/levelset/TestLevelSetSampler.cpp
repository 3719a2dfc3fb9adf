// Sampling: the trilinear interpolant and its gradient, and thread safety.
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <random>
#include <thread>

using namespace lsdem;

// A trilinear interpolant reproduces any function of the form a + b·x + c·y + d·z + e·xy + ...
// exactly; take φ = 0.5 + 2x - y + 3z + xy·0.25 on a grid with an offset origin.
TEST(LevelSetSampler, ReproducesTrilinearFunctionsAndTheirGradients)
{
    initializeOpenVdb();
    LevelSetGrid ls;
    ls.voxelSize = 0.25;
    ls.origin = Vec3(-1.0, -2.0, 0.5);
    const auto grid = openvdb::FloatGrid::create(100.0f);
    auto f = [](const Vec3& p) { return 0.5 + 2 * p.x() - p.y() + 3 * p.z() + 0.25 * p.x() * p.y(); };
    auto accessor = grid->getAccessor();
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            for (int k = 0; k < 16; ++k)
                accessor.setValue(openvdb::Coord(i, j, k),
                                  float(f(ls.origin + ls.voxelSize * Vec3(i, j, k))));
    ls.grid = toLevelSetGrid(*grid);
    LevelSetSampler sampler(ls);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 14.5 * 0.25);  // all 8 corners set
    for (int n = 0; n < 1000; ++n) {
        const Vec3 p = ls.origin + Vec3(u(rng), u(rng), u(rng));
        const LevelSetSample s = sampler.sample(p);
        EXPECT_NEAR(s.phi, f(p), 1e-5);  // float storage of values up to ~20
        const Vec3 grad(2 + 0.25 * p.y(), -1 + 0.25 * p.x(), 3);
        EXPECT_NEAR((s.gradient - grad).norm(), 0.0, 1e-4);
    }
}

// The cell of a point is found by ⌊index⌋ also where the index is negative or a whole number
// (a point on a cell face): φ is the trilinear interpolant of that cell's stored corners,
// computed here with std::floor, of a function that is not trilinear (so a neighbouring cell's
// interpolant, extrapolated, would differ by about 0.05·(distance into it)²). On a face across
// x, ∂φ/∂x is the mean of the two cells' derivatives there.
TEST(LevelSetSampler, NegativeAndWholeIndicesFindTheirCell)
{
    initializeOpenVdb();
    LevelSetGrid ls;
    ls.voxelSize = 0.5;
    ls.origin = Vec3(0.0, 0.0, 0.0);
    const auto grid = openvdb::FloatGrid::create(100.0f);
    auto f = [](const Vec3& p) {
        return 0.5 + 0.3 * p.x() + 0.05 * (p.x() * p.x() - p.y() * p.y() + p.z() * p.z());
    };
    auto accessor = grid->getAccessor();
    for (int i = -8; i < 8; ++i)
        for (int j = -8; j < 8; ++j)
            for (int k = -8; k < 8; ++k)
                accessor.setValue(openvdb::Coord(i, j, k),
                                  float(f(ls.origin + ls.voxelSize * Vec3(i, j, k))));
    ls.grid = toLevelSetGrid(*grid);
    LevelSetSampler sampler(ls);
    auto trilinear = [&](const Vec3& p) {
        const Vec3 index = (p - ls.origin) / ls.voxelSize;
        const Vec3 base(std::floor(index.x()), std::floor(index.y()), std::floor(index.z()));
        const Vec3 t = index - base;
        double sum = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 offset(corner & 1, (corner >> 1) & 1, corner >> 2);
            const double weight = (offset.x() ? t.x() : 1.0 - t.x()) *
                                  (offset.y() ? t.y() : 1.0 - t.y()) *
                                  (offset.z() ? t.z() : 1.0 - t.z());
            const openvdb::Coord c(int(base.x() + offset.x()), int(base.y() + offset.y()),
                                   int(base.z() + offset.z()));
            sum += weight * ls.grid->value(c);  // as stored (quantized): read back
        }
        return sum;
    };
    // ∂φ/∂x in the cell whose lower x index is @a cellX, at @a p's y and z.
    auto xDerivative = [&](int cellX, const Vec3& p) {
        const Vec3 index = (p - ls.origin) / ls.voxelSize;
        const double by = std::floor(index.y()), bz = std::floor(index.z());
        const double ty = index.y() - by, tz = index.z() - bz;
        double sum = 0.0;
        for (int corner = 0; corner < 4; ++corner) {
            const int oy = corner & 1, oz = corner >> 1;
            const double weight = (oy ? ty : 1.0 - ty) * (oz ? tz : 1.0 - tz);
            const int y = int(by) + oy, z = int(bz) + oz;
            sum += weight * (ls.grid->value(openvdb::Coord(cellX + 1, y, z)) -
                             ls.grid->value(openvdb::Coord(cellX, y, z)));
        }
        return sum / ls.voxelSize;
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-3.4, 3.4);  // indices -6.8 to 6.8
    std::uniform_int_distribution<int> whole(-6, 6);
    for (int n = 0; n < 2000; ++n) {
        Vec3 p(u(rng), u(rng), u(rng));
        if (n % 4 == 0) p.x() = 0.5 * whole(rng);  // on a cell face along x
        if (n % 8 == 0) p.y() = 0.5 * whole(rng);
        const double expected = trilinear(p);
        LevelSetCell cell;
        EXPECT_NEAR(sampler.sample(p, cell).phi, expected, 1e-12) << p.transpose();
        // On a face both cells give the same φ: the cell kept must still be ⌊index⌋'s.
        const Vec3 index = (p - ls.origin) / ls.voxelSize;
        const std::array<int, 3> lower = {int(std::floor(index.x())), int(std::floor(index.y())),
                                          int(std::floor(index.z()))};
        EXPECT_EQ(cell.base, lower) << p.transpose();
        EXPECT_NEAR(sampler.phi(p), expected, 1e-12) << p.transpose();
        if (n % 4 == 0) {
            const int face = int(std::lround(p.x() / ls.voxelSize));
            const double mean = 0.5 * (xDerivative(face - 1, p) + xDerivative(face, p));
            EXPECT_NEAR(sampler.sample(p).gradient.x(), mean, 1e-9) << p.transpose();
        }
    }
}

// A point that walks in small steps (as a node does over a run) and keeps its cell gets the
// same bits as a fresh sample each time, whether it stayed in its cell or moved on.
TEST(LevelSetSampler, ACellKeptBetweenSamplesGivesTheSameBits)
{
    initializeOpenVdb();
    BakeOptions options;
    options.voxelSize = 0.1;
    options.nodeSpacing = 0.5;
    std::vector<std::string> warnings;
    const GrainAsset sphere = bakeAnalytic(AnalyticShape::sphere(1.0), options, warnings);
    const LevelSetGrid& ls = *sphere.levelSet;
    LevelSetSampler sampler(ls);
    LevelSetCell cell;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Vec3 p(0.93, 0.05, -0.2);
    int reused = 0, moved = 0;
    for (int n = 0; n < 2000; ++n) {
        p += 0.01 * Vec3(u(rng), u(rng), u(rng));  // a tenth of a voxel per axis at most
        const std::array<int, 3> before = cell.base;
        const LevelSetSample kept = sampler.sample(p, cell);
        const LevelSetSample fresh = sampler.sample(p);
        ASSERT_EQ(kept.phi, fresh.phi) << n;
        ASSERT_EQ(kept.gradient, fresh.gradient) << n;
        (cell.base == before ? reused : moved) += 1;
    }
    EXPECT_GT(reused, 1000);  // mostly in the cell of the last sample ...
    EXPECT_GT(moved, 20);     // ... but crossing into others too
}

TEST(LevelSetSampler, ManyThreadsSeeTheSameValuesAsOne)
{
    std::vector<std::string> warnings;
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.3;
    const GrainAsset asset = bakeAnalytic(AnalyticShape::ellipsoid(2, 1.5, 1), o, warnings);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2.5, 2.5);
    std::vector<Vec3> points(100000);
    for (Vec3& p : points) p = Vec3(u(rng), u(rng), u(rng));

    std::vector<LevelSetSample> serial(points.size());
    LevelSetSampler one(*asset.levelSet);
    for (size_t i = 0; i < points.size(); ++i) serial[i] = one.sample(points[i]);

    // Four plain threads, each with its own sampler, interleaved over the same points.
    std::vector<LevelSetSample> threaded(points.size());
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            LevelSetSampler mine(*asset.levelSet);
            for (size_t i = t; i < points.size(); i += 4) threaded[i] = mine.sample(points[i]);
        });
    for (auto& th : threads) th.join();
    // And TBB tasks, one sampler per chunk.
    std::vector<LevelSetSample> tasks(points.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 512), [&](const auto& r) {
        LevelSetSampler mine(*asset.levelSet);
        for (size_t i = r.begin(); i != r.end(); ++i) tasks[i] = mine.sample(points[i]);
    });
    for (size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(serial[i].phi, threaded[i].phi);
        ASSERT_EQ(serial[i].gradient, threaded[i].gradient);
        ASSERT_EQ(serial[i].phi, tasks[i].phi);
        ASSERT_EQ(serial[i].gradient, tasks[i].gradient);
    }
}

// A level set that carries an exact distance (LevelSetGrid::exact) is sampled as that distance,
// not as its voxels: the same bits as the closed form, while the voxels' interpolant differs by
// its interpolation error.
TEST(LevelSetSampler, AnExactDistanceIsSampledInsteadOfTheVoxels)
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.3;
    std::vector<std::string> warnings;
    const AnalyticShape sphere = AnalyticShape::sphere(1.0);
    const GrainAsset a = bakeAnalytic(sphere, o, warnings);
    LevelSetGrid exactGrid = *a.levelSet;
    exactGrid.exact = sphere.exactDistance();
    LevelSetSampler voxels(*a.levelSet), exact(exactGrid);
    double largestVoxelError = 0.0;
    for (const Vec3& p : {Vec3(0.97, 0.05, 0.11), Vec3(-0.33, 0.71, -0.61), Vec3(0.2, -1.02, 0.03)}) {
        const LevelSetSample s = exact.sample(p);
        EXPECT_EQ(s.phi, p.norm() - 1.0);
        EXPECT_EQ(exact.phi(p), p.norm() - 1.0);
        // (p − closest point)/φ: round-off of ε·|p|/|φ| near the surface (|φ| ≥ 0.02 here).
        EXPECT_LT((s.gradient - p.normalized()).norm(), 1e-12);
        largestVoxelError = std::max(largestVoxelError, std::abs(voxels.phi(p) - s.phi));
    }
    // The voxels' trilinear interpolant errs by about h²/(8R) on a sphere, never zero here.
    EXPECT_GT(largestVoxelError, 1e-6);
    EXPECT_LT(largestVoxelError, 0.1 * 0.1);
}
