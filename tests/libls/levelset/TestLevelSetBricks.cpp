// The level set as held in memory (bricks of 24-bit values, 16-bit codes on a plane, or 16-bit
// deep codes): every stored value against the float grid it was made from, the sign kept,
// tiles kept, and a save/load round trip to the same bits.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <gtest/gtest.h>

#include <openvdb/tools/LevelSetSphere.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>

using namespace lsdem;

namespace {

/// The float value bakeAnalytic stores at voxel @a c of a sphere of @a radius centred at the
/// asset origin (the exact distance, rounded to float, capped at the background).
float bakedSphereValue(const LevelSetGrid& ls, double radius, float background,
                       const openvdb::Coord& c)
{
    const Vec3 p = ls.origin + ls.voxelSize * Vec3(c.x(), c.y(), c.z());
    const double d = p.norm() - radius;
    return d >= background ? background : float(d);
}

/// The asset: a sphere of radius kRadius at voxels of kVox (R/20), interior filled.
constexpr double kRadius = 1.0, kVox = 0.05;
GrainAsset bakedSphere()
{
    BakeOptions o;
    o.voxelSize = kVox;
    o.nodeSpacing = 0.2;
    std::vector<std::string> warnings;
    return bakeAnalytic(AnalyticShape::sphere(kRadius), o, warnings);
}

/// The trilinear interpolant at @a index (index space) of the corner values @a valueAt(Coord).
template <typename ValueAt>
double trilinear(const Vec3& index, ValueAt&& valueAt)
{
    const openvdb::Coord base(int(std::floor(index.x())), int(std::floor(index.y())),
                              int(std::floor(index.z())));
    const Vec3 f = index - Vec3(base.x(), base.y(), base.z());
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const int ox = corner & 1, oy = (corner >> 1) & 1, oz = corner >> 2;
        const double w =
            (ox ? f.x() : 1 - f.x()) * (oy ? f.y() : 1 - f.y()) * (oz ? f.z() : 1 - f.z());
        sum += w * double(valueAt(base.offsetBy(ox, oy, oz)));
    }
    return sum;
}

} // namespace

// The asset: a sphere at R/20 (a grain 40 voxels across). Every voxel of the baked grid
// holds its float value within 2^-21 of the largest |φ| of its 4³ brick (at most |φ| + 3√3
// voxels, φ being a distance) as a 24-bit value; a plane brick rounds that again to its step
// (at most 2^-9 voxel with 8-bit remainders, 2^-17 with 16: within half of it, or a whole one
// where the sign would be lost). In the band, where contacts are decided, that is under 2^-9 +
// 2^-21·3√3 = 1.96e-3 voxel (9.8e-4 but for values within 2^-10 voxel of the surface). For comparison, trilinear interpolation of
// this sphere's distance already errs by up to 3h²/(8R) = 0.019 voxel: the storage adds at
// most a tenth of that, a twentieth away from the surface. Bricks 3 or more voxels inside are
// deep: 16 bits, each value below the float by less than a deep step (at most 2^-12 voxel),
// never above it. Near the surface a sphere's distance is nearly a plane over a brick: nearly
// every shell brick is a plane brick.
TEST(LevelSetBricks, BakedSphereValuesAreTheFloatGridsWithinTheBound)
{
    const double radius = kRadius, vox = kVox;
    const GrainAsset asset = bakedSphere();
    const LevelSetGrid& ls = *asset.levelSet;
    const LevelSetBricks& bricks = *ls.grid;
    const float background = bricks.background();
    ASSERT_FLOAT_EQ(background, float(asset.exteriorBandVoxels * vox));

    const int n = int(std::ceil(radius / vox)) + asset.exteriorBandVoxels + 1;  // as bakeAnalytic
    const double deepStep = bricks.deepStep();
    ASSERT_GT(deepStep, std::ldexp(vox, -13));
    ASSERT_LE(deepStep, std::ldexp(vox, -12));
    double bandError = 0.0;  // voxels
    size_t inBand = 0, differ = 0, inDeepBricks = 0, inPlaneBricks = 0;
    for (int i = 0; i <= 2 * n; ++i)
        for (int j = 0; j <= 2 * n; ++j)
            for (int k = 0; k <= 2 * n; ++k) {
                const openvdb::Coord c(i, j, k);
                const float v = bakedSphereValue(ls, radius, background, c);
                const float s = bricks.value(c);
                ASSERT_EQ(bricks.isValueOn(c), v != background) << c;
                // The sign is kept exactly: it decides contact.
                ASSERT_EQ(v < 0.0f, s < 0.0f) << c << " " << v << " " << s;
                ASSERT_EQ(v > 0.0f, s > 0.0f) << c << " " << v << " " << s;
                const double error = std::abs(double(s) - double(v));
                // The 24-bit rounding, within 2^-21 of the brick's largest |value|.
                const double wide = LevelSetBricks::kRelativeError *
                                    (std::abs(double(v)) + 3.0 * std::sqrt(3.0) * vox);
                const uint32_t brick = bricks.brickAt(c);
                if (bricks.isDeep(brick)) {
                    ASSERT_LE(s, -LevelSetBricks::kDeepVoxels * vox) << c;
                    // Rounded down from the 24-bit value, by less than a deep step.
                    ASSERT_LE(s, v + wide) << c;
                    ASSERT_LT(v - s, deepStep + wide) << c;
                    ++inDeepBricks;
                } else if (bricks.isPlane(brick)) {
                    ASSERT_LE(bricks.step(brick), (bricks.isNarrow(brick)
                                                       ? LevelSetBricks::kNarrowPlaneStepVoxels
                                                       : LevelSetBricks::kPlaneStepVoxels) *
                                                      vox)
                        << c;
                    ASSERT_LE(error, wide + bricks.step(brick)) << c;
                    ++inPlaneBricks;
                } else {
                    ASSERT_LE(error, wide) << c;
                }
                differ += error > 0.0;
                if (std::abs(v) <= background) {
                    ++inBand;
                    bandError = std::max(bandError, error / vox);
                }
            }
    EXPECT_GT(inBand, 20000u);
    // A sphere of 20 voxels: bricks wholly 3 voxels or more inside hold about a quarter of
    // the values within 2 voxels of it or inside.
    EXPECT_EQ(inDeepBricks, bricks.deepBrickCount() * LevelSetBricks::kVoxels);
    EXPECT_GT(inDeepBricks, 8000u);
    std::cout << "[ measured ] R/20 sphere: " << bricks.planeBrickCount() << " plane ("
              << bricks.narrowBrickCount() << " of them 8-bit), "
              << bricks.deepBrickCount() << " deep of " << bricks.brickCount()
              << " bricks; largest error in the band " << bandError << " voxel\n";
    EXPECT_EQ(inPlaneBricks, bricks.planeBrickCount() * LevelSetBricks::kVoxels);
    const size_t wideBricks =
        bricks.brickCount() - bricks.deepBrickCount() - bricks.planeBrickCount();
    // (Wide ones include the shared, and the corners of the band's edge where a few voxels
    // below the cap leave the others too far from any plane: 645 plane and 67 wide bricks.)
    EXPECT_GT(bricks.planeBrickCount(), 9 * wideBricks);
    // A sphere is smooth: most of its plane bricks hold 8 bits (not those where the band's cap
    // leaves too few voxels to fit a quadratic: 552 of 651).
    EXPECT_GT(bricks.narrowBrickCount(), bricks.planeBrickCount() * 4 / 5);
    EXPECT_GT(differ, inBand / 2);  // values are really quantised ...
    EXPECT_LT(bandError, 1.96e-3);  // ... and within 1.96e-3 voxel in the band
    EXPECT_GT(bandError, 1e-8);

    // The sampler interpolates the stored values: it is within the same bound of the trilinear
    // interpolant of the float values (a convex combination of the corners); within a deep
    // step where a corner may lie in a deep brick (a point more than kDeepVoxels − √3 inside).
    // It reads the corners of a cell within one brick by its own path (the plane's codes
    // added corner by corner), so this also checks that path against decode().
    LevelSetSampler sampler(ls);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> direction(-1.0, 1.0), depth(-3.0 * vox, 3.0 * vox);
    const double onlyWideBricks = (LevelSetBricks::kDeepVoxels - std::sqrt(3.0)) * vox;
    for (int m = 0; m < 2000; ++m) {
        const double d = depth(rng);
        const Vec3 p =
            Vec3(direction(rng), direction(rng), direction(rng)).normalized() * (radius + d);
        const double floatTrilinear = trilinear(
            (p - ls.origin) / vox,
            [&](const openvdb::Coord& c) { return bakedSphereValue(ls, radius, background, c); });
        const double tolerance = 1.96e-3 * vox + (-d < onlyWideBricks ? 0.0 : deepStep);
        EXPECT_NEAR(sampler.phi(p), floatTrilinear, tolerance) << p.transpose();
    }
}

// An OpenVDB narrow-band level set (inactive interior tiles at −background): the tiles keep
// their value and sign, and turning the bricks back into a float grid and into bricks again
// gives the same values, states and memory, bit for bit (what a saved and loaded asset needs).
TEST(LevelSetBricks, TilesAndRoundTripsAreKeptExactly)
{
    initializeOpenVdb();
    const float vox = 0.05f;
    const auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
        1.3f, openvdb::Vec3f(0.11f, -0.07f, 0.03f), vox, 3.0f);
    const auto bricks = toLevelSetGrid(*grid);
    EXPECT_EQ(bricks->activeVoxelCount(), grid->activeVoxelCount());
    EXPECT_EQ(bricks->evalActiveVoxelBoundingBox(), grid->evalActiveVoxelBoundingBox());
    EXPECT_EQ(bricks->background(), grid->background());
    const openvdb::Coord centre(2, -1, 1);  // deep inside: an interior tile
    ASSERT_FALSE(grid->tree().isValueOn(centre));
    EXPECT_EQ(bricks->value(centre), -grid->background());
    auto accessor = grid->getConstAccessor();
    openvdb::CoordBBox all = grid->evalActiveVoxelBoundingBox();
    all.expand(4);
    for (auto c = all.begin(); c; ++c) {
        const float v = accessor.getValue(*c), s = bricks->value(*c);
        ASSERT_EQ(accessor.isValueOn(*c), bricks->isValueOn(*c)) << *c;
        ASSERT_EQ(v < 0.0f, s < 0.0f) << *c;
        const uint32_t brick = bricks->brickAt(*c);
        ASSERT_LE(std::abs(s - v), LevelSetBricks::kRelativeError * 2.0f * grid->background() +
                                       (bricks->isPlane(brick) ? bricks->step(brick) : 0.0f))
            << *c;
    }

    const openvdb::FloatGrid::Ptr standard = toFloatGrid(*bricks);
    EXPECT_EQ(standard->transform(), grid->transform());
    const auto again = toLevelSetGrid(*standard);
    EXPECT_GT(bricks->planeBrickCount(), 0u);
    EXPECT_EQ(again->planeBrickCount(), bricks->planeBrickCount());
    EXPECT_EQ(again->memUsage(), bricks->memUsage());
    EXPECT_EQ(again->activeVoxelCount(), bricks->activeVoxelCount());
    for (auto c = all.begin(); c; ++c) {
        ASSERT_EQ(again->value(*c), bricks->value(*c)) << *c;
        ASSERT_EQ(again->isValueOn(*c), bricks->isValueOn(*c)) << *c;
    }
}

// The interior of a baked grain in deep bricks: turned into a float grid and back it gives the
// same bricks (deep ones included), values and memory, bit for bit, and the sampler reads a
// cell in deep bricks as the trilinear interpolant of the values stored there.
TEST(LevelSetBricks, DeepBricksRoundTripExactlyAndSampleAsStored)
{
    const GrainAsset asset = bakedSphere();
    const LevelSetGrid& ls = *asset.levelSet;
    const LevelSetBricks& bricks = *ls.grid;
    ASSERT_GT(bricks.deepBrickCount(), 100u);

    const auto again = toLevelSetGrid(*toFloatGrid(bricks));
    EXPECT_EQ(again->deepBrickCount(), bricks.deepBrickCount());
    EXPECT_EQ(again->planeBrickCount(), bricks.planeBrickCount());
    EXPECT_EQ(again->memUsage(), bricks.memUsage());
    openvdb::CoordBBox all = bricks.tableBox();
    all.expand(1);
    for (auto c = all.begin(); c; ++c) {
        ASSERT_EQ(again->value(*c), bricks.value(*c)) << *c;
        ASSERT_EQ(again->isValueOn(*c), bricks.isValueOn(*c)) << *c;
    }

    LevelSetSampler sampler(ls);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coordinate(-0.8, 0.8);
    int inDeepCells = 0;
    for (int m = 0; m < 3000; ++m) {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        bool deep = true;
        const double stored = trilinear((p - ls.origin) / kVox, [&](const openvdb::Coord& c) {
            deep &= bricks.isDeep(bricks.brickAt(c));
            return bricks.value(c);
        });
        inDeepCells += deep;
        ASSERT_NEAR(sampler.phi(p), stored, 1e-12) << p.transpose();
    }
    EXPECT_GT(inDeepCells, 300);
}

// Which bricks are stored deep, at the edges of the rule (voxels of 1, so the deep step is
// 2^-12 and the threshold −3): decided on the values as 24 bits would hold them, and kept so
// by a round trip through a float grid (the same kind, values and memory).
TEST(LevelSetBricks, DeepBricksAtTheEdgesOfTheRule)
{
    initializeOpenVdb();
    struct Case
    {
        const char* what;
        std::function<float(int)> value;  // of voxel k of the brick at the origin
        bool deep;
    };
    const Case cases[] = {
        {"deep", [](int k) { return -20.0f - 0.01f * float(k); }, true},
        // −3 + 2^-22 is −3 in 24 bits (steps of 2^-19 here): deep, and deep again when loaded.
        {"at the threshold in 24 bits",
         [](int k) { return k == 0 ? -3.0f + std::ldexp(1.0f, -22) : -4.0f - 0.01f * float(k); },
         true},
        {"above it in 24 bits",
         [](int k) { return k == 0 ? -3.0f + std::ldexp(1.0f, -18) : -4.0f - 0.01f * float(k); },
         false},
        // 20 voxels apart: more than 65535 deep steps.
        {"too wide a range", [](int k) { return -10.0f - 20.0f * float(k) / 63.0f; }, false},
        // Beyond 2^22 deep steps (1024 voxels) a deep value would not be a 24-bit one.
        {"too deep", [](int k) { return -2000.0f - 0.01f * float(k); }, false},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        auto grid = openvdb::FloatGrid::create(3.0f);
        auto accessor = grid->getAccessor();
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k)
            accessor.setValueOn(openvdb::Coord(k >> 4, (k >> 2) & 3, k & 3), c.value(k));
        const auto bricks = toLevelSetGrid(*grid);
        ASSERT_EQ(bricks->deepStep(), std::ldexp(1.0f, -12));
        const uint32_t b = bricks->brick(0, 0, 0);
        EXPECT_EQ(bricks->isDeep(b), c.deep);
        EXPECT_EQ(bricks->deepBrickCount(), c.deep ? 1u : 0u);
        double largest = 0.0;
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k)
            largest = std::max(largest, std::abs(double(c.value(k))));
        const double wide = LevelSetBricks::kRelativeError * 2.0 * largest;  // 24-bit rounding
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
            const openvdb::Coord at(k >> 4, (k >> 2) & 3, k & 3);
            const double v = c.value(k), stored = bricks->value(at);
            EXPECT_LE(stored, v + wide) << at;
            EXPECT_GT(stored, v - wide - (c.deep ? bricks->deepStep() : 0.0)) << at;
        }
        const auto again = toLevelSetGrid(*toFloatGrid(*bricks));
        EXPECT_EQ(again->isDeep(again->brick(0, 0, 0)), c.deep);
        EXPECT_EQ(again->memUsage(), bricks->memUsage());
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
            const openvdb::Coord at(k >> 4, (k >> 2) & 3, k & 3);
            ASSERT_EQ(again->value(at), bricks->value(at)) << at;
        }
    }
}

// Which bricks are stored on a plane, and in how many bits (voxels of 1, so the coarsest plane
// steps are 2^-9 for 8 bits, where 255 codes span 0.498 voxel, and 2^-17 for 16, where 65535
// span 0.5): a flat face's distance is a plane exactly and keeps its 24-bit values (the step
// theirs) in 8 bits; a sphere's of radius 20 strays from a plane by about 2.25/20 voxel over
// the brick and fits 8 bits at a coarser step, within half of it of the 24-bit values; a
// polyhedron's edge near a corner of the brick strays by 0.47 voxel from a plane, which 255
// codes would span, but they would move the flat face beside it, which interpolation
// reproduces exactly, and a quadratic leaves 0.67 of that spread: 16 bits; a sphere of radius
// 4 strays by 0.56 voxel or more and stays wide, as does a sharp crease through the brick's
// middle (the distance to a ridge). Each comes back from a float grid as the same kind, values
// and memory.
TEST(LevelSetBricks, PlaneBricksAtTheEdgesOfTheRule)
{
    initializeOpenVdb();
    struct Case
    {
        const char* what;
        std::function<double(int, int, int)> value;  // at voxel (x, y, z) of the brick
        bool plane, narrow, lossless;
    };
    // The spheres' surfaces cross the brick at x ≈ 1.7.
    const Vec3 centre(-18.3, 0.4, 0.7), smallCentre(-2.3, 1.6, 1.4);
    const Case cases[] = {
        {"a flat face", [](int x, int y, int z) { return 0.6 * x - 0.48 * y + 0.64 * z - 1.1; },
         true, true, true},
        {"a sphere of 20 voxels",
         [&](int x, int y, int z) { return (Vec3(x, y, z) - centre).norm() - 20.0; }, true, true,
         false},
        {"an edge near a corner",
         [&](int x, int y, int z) {
             const Vec3 p(x, y, z);
             return std::max(Vec3(0.1, 0.15, 1.0).normalized().dot(p) - 1.6,
                             Vec3(1.0, -0.2, 0.1).normalized().dot(p) - 3.75);
         },
         true, false, false},
        {"a sphere of 4 voxels",
         [&](int x, int y, int z) { return (Vec3(x, y, z) - smallCentre).norm() - 4.0; }, false,
         false, false},
        {"a crease", [](int x, int y, int z) { return std::abs(x - 1.5) - 0.5 + 0.1 * y + 0.05 * z; },
         false, false, false},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        auto grid = openvdb::FloatGrid::create(3.0f);
        auto accessor = grid->getAccessor();
        double largest = 0.0;
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
            const openvdb::Coord at(k >> 4, (k >> 2) & 3, k & 3);
            accessor.setValueOn(at, float(c.value(at.x(), at.y(), at.z())));
            largest = std::max(largest, std::abs(double(accessor.getValue(at))));
        }
        const auto bricks = toLevelSetGrid(*grid);
        const uint32_t b = bricks->brick(0, 0, 0);
        EXPECT_EQ(bricks->isPlane(b), c.plane);
        EXPECT_EQ(bricks->isNarrow(b), c.narrow);
        EXPECT_FALSE(bricks->isDeep(b));
        // The 24-bit step of the brick: 2^(c − 22), 2^c the largest |value| rounded up.
        const double wideStep = std::ldexp(1.0, int(std::ceil(std::log2(largest))) - 22);
        if (c.plane) {
            EXPECT_LE(bricks->step(b), c.narrow ? LevelSetBricks::kNarrowPlaneStepVoxels
                                                : LevelSetBricks::kPlaneStepVoxels);
            if (c.lossless)
                EXPECT_EQ(bricks->step(b), wideStep);
            else
                EXPECT_GT(bricks->step(b), wideStep);
        }
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
            const openvdb::Coord at(k >> 4, (k >> 2) & 3, k & 3);
            const double v = accessor.getValue(at), stored = bricks->value(at);
            const double allowed = 0.5 * wideStep + (c.plane && !c.lossless ? 0.5 * bricks->step(b) : 0.0);
            EXPECT_LE(std::abs(stored - v), allowed) << at;
            EXPECT_EQ(stored < 0.0, v < 0.0) << at;
        }
        const auto again = toLevelSetGrid(*toFloatGrid(*bricks));
        EXPECT_EQ(again->isPlane(again->brick(0, 0, 0)), c.plane);
        EXPECT_EQ(again->isNarrow(again->brick(0, 0, 0)), c.narrow);
        EXPECT_EQ(again->memUsage(), bricks->memUsage());
        for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
            const openvdb::Coord at(k >> 4, (k >> 2) & 3, k & 3);
            ASSERT_EQ(again->value(at), bricks->value(at)) << at;
        }
    }
}

// The bricks are read and encoded in parallel, but numbered in the order of their places: one
// thread and two give the same table, the same brick for every place and the same bytes, for
// a narrow band with interior tiles and for a baked grain's filled interior (deep bricks).
TEST(LevelSetBricks, SameBricksOnAnyThreadCount)
{
    initializeOpenVdb();
    const GrainAsset baked = bakedSphere();
    for (const openvdb::FloatGrid::Ptr& grid :
         {openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
              1.3f, openvdb::Vec3f(0.11f, -0.07f, 0.03f), 0.05f, 3.0f),
          toFloatGrid(*baked.levelSet->grid)}) {
        auto bricksOn = [&](int threads) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      size_t(threads));
            return toLevelSetGrid(*grid);
        };
        const auto one = bricksOn(1), two = bricksOn(2);
        ASSERT_EQ(one->deepBrickCount(), two->deepBrickCount());
        ASSERT_EQ(one->memUsage(), two->memUsage());
        ASSERT_EQ(one->origin(), two->origin());
        const openvdb::CoordBBox table = one->tableBox();
        ASSERT_EQ(table, two->tableBox());
        ASSERT_FALSE(table.empty());
        const openvdb::Coord size = table.dim();
        constexpr int kDim = LevelSetBricks::kDim;
        const openvdb::Coord places(size.x() / kDim, size.y() / kDim, size.z() / kDim);
        uint32_t highest = 0;
        for (int x = 0; x < places.x(); ++x)
            for (int y = 0; y < places.y(); ++y)
                for (int z = 0; z < places.z(); ++z) {
                    ASSERT_EQ(one->brick(x, y, z), two->brick(x, y, z))
                        << x << " " << y << " " << z;
                    highest = std::max(highest, one->brick(x, y, z));
                }
        EXPECT_GT(highest, 100u);  // many bricks, in both threads' shares
        for (uint32_t b = 0; b <= highest; ++b) {
            ASSERT_EQ(one->step(b), two->step(b)) << b;
            ASSERT_EQ(one->isDeep(b), two->isDeep(b)) << b;
            ASSERT_EQ(one->isPlane(b), two->isPlane(b)) << b;
            const int bytes = (one->isWide(b) ? 3 : one->isNarrow(b) ? 1 : 2) * LevelSetBricks::kVoxels;
            ASSERT_TRUE(std::equal(one->codes(b), one->codes(b) + bytes, two->codes(b))) << b;
            // (A plane or deep brick's base and plane are part of its values: compare them.)
            for (int v = 0; v < LevelSetBricks::kVoxels; ++v)
                ASSERT_EQ(one->decode(b, v), two->decode(b, v)) << b;
        }
    }
}

// The bricks' active states are kept as the distinct masks and an index a brick: 2 bytes up to
// 65,536 distinct masks, 4 beyond. A grid of 41³ bricks whose every brick has a mask of its
// own (its number's bits in its first 17 voxels' states) takes the 4-byte path; each voxel's
// state and the active count come back as set, and through a float grid the same again.
TEST(LevelSetBricks, ActiveStatesOfManyDistinctMasks)
{
    initializeOpenVdb();
    constexpr int kPlaces = 41, kDim = LevelSetBricks::kDim;
    auto grid = openvdb::FloatGrid::create(5.0f);
    auto accessor = grid->getAccessor();
    openvdb::Index64 active = 0;
    const auto isActive = [](int number, int k) { return k < 17 && ((number >> k) & 1) != 0; };
    for (int bx = 0; bx < kPlaces; ++bx)
        for (int by = 0; by < kPlaces; ++by)
            for (int bz = 0; bz < kPlaces; ++bz) {
                const int number = (bx * kPlaces + by) * kPlaces + bz + 1;
                for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
                    const openvdb::Coord c = openvdb::Coord(bx * kDim, by * kDim, bz * kDim) +
                                             LevelSetBricks::voxelOf(k);
                    const float value = 0.25f * float(k % 7) - 1.0f;  // varying, all finite
                    if (isActive(number, k)) {
                        accessor.setValueOn(c, value);
                        ++active;
                    } else {
                        accessor.setValueOff(c, value);
                    }
                }
            }
    const auto bricks = toLevelSetGrid(*grid);
    EXPECT_EQ(bricks->activeVoxelCount(), active);
    for (int bx = 0; bx < kPlaces; bx += 5)
        for (int by = 0; by < kPlaces; by += 3)
            for (int bz = 0; bz < kPlaces; ++bz) {
                const int number = (bx * kPlaces + by) * kPlaces + bz + 1;
                for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
                    const openvdb::Coord c = openvdb::Coord(bx * kDim, by * kDim, bz * kDim) +
                                             LevelSetBricks::voxelOf(k);
                    ASSERT_EQ(bricks->isValueOn(c), isActive(number, k)) << c;
                }
            }
    const auto again = toLevelSetGrid(*toFloatGrid(*bricks));
    EXPECT_EQ(again->activeVoxelCount(), active);
    EXPECT_EQ(again->memUsage(), bricks->memUsage());
}

// Grids lsdem cannot hold as bricks are refused with an lsdem::Error naming the problem: a
// value that is not a number, and values spread over a box too large for a dense table.
TEST(LevelSetBricks, RefusesNonFiniteValuesAndHugeBoxes)
{
    initializeOpenVdb();
    auto nan = openvdb::FloatGrid::create(1.0f);
    nan->tree().setValue(openvdb::Coord(3, 4, 5), std::nanf(""));
    EXPECT_THROW(toLevelSetGrid(*nan), Error);
    auto spread = openvdb::FloatGrid::create(1.0f);
    spread->tree().setValue(openvdb::Coord(0, 0, 0), -1.0f);
    spread->tree().setValue(openvdb::Coord(8000, 8000, 8000), -1.0f);
    EXPECT_THROW(toLevelSetGrid(*spread), Error);
}

namespace {

/// levelSetSlopeBound's definition, cell by cell: over the cells with a corner in the table
/// (or the layer before it) and a corner at φ ≥ 0, the largest root of the sum of the squares
/// of the cell's largest difference along each axis, over the voxel size.
double slopeBoundVoxelByVoxel(const LevelSetGrid& levelSet)
{
    const LevelSetBricks& grid = *levelSet.grid;
    const openvdb::CoordBBox table = grid.tableBox();
    if (table.empty()) return 0.0;
    double largest = 0.0;
    const openvdb::Coord lo = table.min().offsetBy(-1), hi = table.max();
    for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
            for (int z = lo.z(); z <= hi.z(); ++z) {
                double v[2][2][2];
                bool outside = false;
                for (int i = 0; i < 2; ++i)
                    for (int j = 0; j < 2; ++j)
                        for (int k = 0; k < 2; ++k) {
                            v[i][j][k] = grid.value(openvdb::Coord(x + i, y + j, z + k));
                            outside |= v[i][j][k] >= 0.0;
                        }
                if (!outside) continue;
                double dx = 0.0, dy = 0.0, dz = 0.0;
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b) {
                        dx = std::max(dx, std::abs(v[1][a][b] - v[0][a][b]));
                        dy = std::max(dy, std::abs(v[a][1][b] - v[a][0][b]));
                        dz = std::max(dz, std::abs(v[a][b][1] - v[a][b][0]));
                    }
                largest = std::max(largest, std::sqrt(dx * dx + dy * dy + dz * dz));
            }
    return largest / levelSet.voxelSize;
}

} // namespace

// The bound is found brick by brick (a window of each brick and one voxel more on its far
// sides, windows of one shared brick skipped): the same number as cell by cell, for a
// sphere, a box (flat faces, interior tiles), an ellipsoid, and grids with one voxel raised
// to a spike outside or lowered, in a brick's first or last layer, at the table's corners
// and just outside them. A voxel lowered deep inside changes no cell with a corner outside,
// and so not the bound.
TEST(LevelSetBricks, SlopeBoundBrickByBrickEqualsVoxelByVoxel)
{
    BakeOptions o;
    o.voxelSize = 0.05;
    o.nodeSpacing = 0.25;
    std::vector<std::string> warnings;
    for (const AnalyticShape& shape :
         {AnalyticShape::sphere(1.0), AnalyticShape::box(1.2, 0.7, 0.45),
          AnalyticShape::ellipsoid(1.0, 0.6, 0.35)}) {
        const GrainAsset asset = bakeAnalytic(shape, o, warnings);
        const double reference = slopeBoundVoxelByVoxel(*asset.levelSet);
        EXPECT_EQ(levelSetSlopeBound(*asset.levelSet), reference);
        EXPECT_GT(reference, 0.0);

        const openvdb::CoordBBox table = asset.levelSet->grid->tableBox();
        const openvdb::Coord sum = table.min() + table.max();
        const openvdb::Coord middle(sum.x() / 2, sum.y() / 2, sum.z() / 2);
        for (const openvdb::Coord& raised :
             {table.min(), table.max(), table.min().offsetBy(-1), table.max().offsetBy(1),
              middle, middle.offsetBy(3), middle.offsetBy(4)}) {
            for (const double by : {7.0, -7.0}) {
                openvdb::FloatGrid::Ptr grid = toFloatGrid(*asset.levelSet->grid);
                auto accessor = grid->getAccessor();
                const double was = accessor.getValue(raised);
                // Raised: a spike 7 voxels outside; lowered: 7 voxels further in.
                const double now = by > 0.0 ? std::max(was, 0.0) + by * o.voxelSize
                                            : was + by * o.voxelSize;
                accessor.setValue(raised, float(now));
                LevelSetGrid stepped = *asset.levelSet;
                stepped.grid = toLevelSetGrid(*grid);
                const double steppedReference = slopeBoundVoxelByVoxel(stepped);
                EXPECT_EQ(levelSetSlopeBound(stepped), steppedReference) << raised << " " << by;
                // The changed voxel counts when a cell around it has a corner outside (it
                // differs from its neighbours along each axis by about 7 voxels there), and
                // changes nothing otherwise.
                bool nearOutside = false;
                for (int i = -1; i <= 1; ++i)
                    for (int j = -1; j <= 1; ++j)
                        for (int k = -1; k <= 1; ++k)
                            nearOutside |= stepped.grid->value(raised.offsetBy(i, j, k)) >= 0.0f;
                if (nearOutside)
                    EXPECT_GT(steppedReference, std::sqrt(3.0) * 5.0) << raised << " " << by;
                else
                    EXPECT_EQ(steppedReference, reference) << raised << " " << by;
            }
        }
    }
}

// The steepest cell of a grid can be one reaching from the background just before the table
// to the table's first voxel: a voxel at −0.5 on the table's low face along one axis, its
// other five neighbours at −0.45, the background at 0.1. Only the edge into the table differs
// by 0.6; the cells that hold it differ by 0.55 along the other two axes (a neighbour at −0.45
// against the background), and no other cell by more than 0.55 along any axis.
TEST(LevelSetBricks, SlopeBoundCountsTheEdgeIntoTheTableFromBelow)
{
    for (int axis = 0; axis < 3; ++axis) {
        auto grid = openvdb::FloatGrid::create(0.1f);
        const openvdb::Coord c(10, 10, 10);
        grid->tree().setValue(c, -0.5f);
        for (int other = 0; other < 3; ++other)
            for (int sign : {-1, 1}) {
                if (other == axis && sign == -1) continue;
                openvdb::Coord n = c;
                n[other] += sign;
                grid->tree().setValue(n, -0.45f);
            }
        LevelSetGrid levelSet;
        levelSet.grid = toLevelSetGrid(*grid);
        levelSet.voxelSize = 1.0;
        EXPECT_EQ(levelSet.grid->tableBox().min()[axis], c[axis]) << axis;
        EXPECT_NEAR(levelSetSlopeBound(levelSet), std::sqrt(0.6 * 0.6 + 2 * 0.55 * 0.55), 1e-6)
            << axis;
        EXPECT_EQ(levelSetSlopeBound(levelSet), slopeBoundVoxelByVoxel(levelSet)) << axis;
    }
}

// levelSetSlopeBound: outside a baked sphere φ is a distance, whose gradient has length 1, so
// the bound is a little above 1 (a cell's largest differences along the three axes come from
// its different edges); and the interpolant never changes faster than it along a segment that
// stays at φ ≥ 0 (checked at 64 points): |φ(x) − φ(y)| ≤ L·|x − y| for random pairs, near and
// far, across the band and out into the background. Inside, where it does not count, the
// distance has its steepest cells (about √3) around the centre. A voxel raised to a spike
// outside gets a steeper bound.
TEST(LevelSetBricks, SlopeBoundHoldsForTheInterpolant)
{
    const GrainAsset asset = bakedSphere();
    const double slope = levelSetSlopeBound(*asset.levelSet);
    EXPECT_EQ(slope, asset.levelSetSlope);  // derived when baked
    EXPECT_GT(slope, 1.0);
    EXPECT_LT(slope, 1.1);

    LevelSetSampler sampler(*asset.levelSet);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> coordinate(-1.4, 1.4), step(-0.2, 0.2);
    double steepest = 0.0;
    int outsidePairs = 0;
    for (int k = 0; k < 200000; ++k) {
        const Vec3 x(coordinate(rng), coordinate(rng), coordinate(rng));
        const Vec3 y = x + (k % 2 ? Vec3(step(rng), step(rng), step(rng))
                                  : Vec3(coordinate(rng), coordinate(rng), coordinate(rng)));
        bool outside = true;
        for (int t = 0; t <= 64 && outside; ++t) outside = sampler.phi(x + (y - x) * (t / 64.0)) >= 0.0;
        if (!outside) continue;
        ++outsidePairs;
        const double ratio = std::abs(sampler.phi(x) - sampler.phi(y)) / (x - y).norm();
        steepest = std::max(steepest, ratio);
        ASSERT_LE(ratio, slope) << x.transpose() << " / " << y.transpose();
    }
    EXPECT_GT(outsidePairs, 20000);
    EXPECT_GT(steepest, 0.9);  // the pairs did cross the distance field

    // A voxel a voxel outside the surface raised by 10 voxels: the bound follows (each of its
    // cells differs by about 10 voxels along each axis: √3 · 10).
    openvdb::FloatGrid::Ptr grid = toFloatGrid(*asset.levelSet->grid);
    const Vec3 index = (Vec3(kRadius + kVox, 0.0, 0.0) - asset.levelSet->origin) / kVox;
    const openvdb::Coord c(int(std::lround(index.x())), int(std::lround(index.y())),
                           int(std::lround(index.z())));
    auto accessor = grid->getAccessor();
    ASSERT_GT(accessor.getValue(c), 0.0f);
    ASSERT_LT(accessor.getValue(c), float(2 * kVox));
    accessor.setValue(c, accessor.getValue(c) + float(10 * kVox));
    LevelSetGrid stepped = *asset.levelSet;
    stepped.grid = toLevelSetGrid(*grid);
    EXPECT_GT(levelSetSlopeBound(stepped), std::sqrt(3.0) * 9.0);
}
