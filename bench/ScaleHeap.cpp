// Building bench_scale's settled heaps (ScaleHeap.h).
#include "ScaleHeap.h"

#include "ProcessMemory.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/simulation/Simulation.h"

#include <malloc.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

namespace lsdem::scalebench {

using bench::resetPeakRss;
using bench::statusBytes;

constexpr int kNodesPerAsset = 500;
constexpr double kMeanSemiAxis = 0.5;     // mm
constexpr double kGap = 0.02;             // mm, between bounding boxes of neighbours
const Eigen::Vector3i kTile(5, 5, 10);   // grains per row, rows and layers of the tile
constexpr long long kTileSettleSteps = 8000;
constexpr double kSettlingGravityFactor = 100.0;  // while the tile settles
constexpr long long kPrefixSteps = 50;   // at full size, before anything is timed

/// The ten sand-like assets, baked once per process (a second each).
const std::vector<std::shared_ptr<const GrainAsset>>& sandAssets()
{
    static const std::vector<std::shared_ptr<const GrainAsset>> assets = [] {
        std::vector<std::shared_ptr<const GrainAsset>> made;
        std::mt19937_64 random(11);
        for (int k = 0; k < kAssetCount; ++k) {
            // a >= b >= c, elongation b/a and flatness c/b in [0.6, 0.95], volume-equivalent
            // radius within ±20 % of the mean.
            const double size = kMeanSemiAxis * (0.8 + 0.4 * uniform01(random));
            const double elongation = 0.6 + 0.35 * uniform01(random);
            const double flatness = 0.6 + 0.35 * uniform01(random);
            const double a = size / std::cbrt(elongation * elongation * flatness);
            const double b = a * elongation, c = b * flatness;
            BakeOptions options;
            options.voxelSize = c / 8.0;
            options.nodePlacement = NodePlacement::Count;
            options.nodeCount = kNodesPerAsset;
            std::vector<std::string> warnings;
            made.push_back(std::make_shared<const GrainAsset>(
                bakeAnalytic(AnalyticShape::ellipsoid(a, b, c), options, warnings)));
        }
        return made;
    }();
    return assets;
}

/// Pairs (grain–grain and grain–wall) with at least one node in contact: exactly those with
/// a shear history after the last step (friction is on).
double contactsNow(const World& w)
{
    double count = 0.0;
    for (const auto& [pair, history] : w.pairHistory) count += history.empty() ? 0.0 : 1.0;
    for (const auto& [pair, history] : w.boundaryHistory) count += history.empty() ? 0.0 : 1.0;
    return count;
}

/// Half-extents along the world axes of an asset's nodes turned by @a orientation.
Vec3 turnedHalfExtents(const GrainAsset& asset, const Quat& orientation)
{
    const Mat3 rotation = orientation.toRotationMatrix();
    Vec3 half = Vec3::Zero();
    for (const Vec3& x : asset.nodes.positions) half = half.cwiseMax((rotation * x).cwiseAbs());
    return half;
}

/// A scene with the assets, the sand and wall materials and their contacts, gravity and
/// damping, and no grains or walls yet.
Scene sandScene()
{
    Scene scene;
    const auto& assets = sandAssets();
    for (int k = 0; k < kAssetCount; ++k) {
        AssetSpec spec;
        spec.name = "sand" + std::to_string(k);
        spec.loaded = assets[size_t(k)];
        scene.assets.push_back(spec);
    }
    scene.materials = {{"sand", 2.65e-9}, {"wall", 0.0}};  // tonne/mm³
    ContactModel model;
    model.formulation = Formulation::Adapted;
    model.testing = NodeTesting::Symmetric;
    model.normalStiffness = 1e3;  // N/mm³ (1 GPa/mm)
    model.shearStiffness = 5e2;
    model.friction = 0.5;
    for (int other : {0, 1}) {
        ContactSpec c;
        c.materialA = 0;
        c.materialB = other;
        c.model = model;
        c.model.damping = ViscousDamping(0.5);
        scene.contacts.push_back(c);
    }
    scene.gravity = Vec3(0, 0, -9810.0);  // mm/s²
    scene.globalDamping = 0.3;
    return scene;
}

/// Walls on the box [lo, hi]: floor and four sides, open at the top.
void addWalls(Scene& scene, const Vec3& lo, const Vec3& hi)
{
    const Vec3 normals[5] = {Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                             -Vec3::UnitY()};
    const Vec3 points[5] = {lo, lo, hi, lo, hi};
    for (int w = 0; w < 5; ++w) {
        BoundarySpec b;
        b.name = "wall" + std::to_string(w);
        b.material = 1;
        b.point = points[w];
        b.normal = normals[w];
        scene.boundaries.push_back(b);
    }
}

/// The loose tile: randomly turned grains packed by their bounding boxes, kGap apart, row by
/// row (x) and layer by layer, in a box of walls kGap outside them (lower corner at 0).
Scene looseTile(Vec3& boxSize)
{
    Scene scene = sandScene();
    const auto& assets = sandAssets();
    std::mt19937_64 random(3);
    Vec3 cursor = Vec3::Constant(kGap), boxMax = Vec3::Zero();
    double rowDepth = 0.0, layerHeight = 0.0;
    for (int n = 0; n < kTile.prod(); ++n) {
        const int column = n % kTile.x(), row = (n / kTile.x()) % kTile.y();
        if (n > 0 && column == 0) {
            cursor.x() = kGap;
            cursor.y() += rowDepth + kGap;
            rowDepth = 0.0;
            if (row == 0) {
                cursor.y() = kGap;
                cursor.z() += layerHeight + kGap;
                layerHeight = 0.0;
            }
        }
        GrainSpec g;
        g.asset = static_cast<int>(random() % kAssetCount);
        g.pose.orientation = randomRotation(random);
        const Vec3 half = turnedHalfExtents(*assets[size_t(g.asset)], g.pose.orientation);
        g.pose.position = cursor + half;
        boxMax = boxMax.cwiseMax(g.pose.position + half);
        scene.grains.push_back(g);
        cursor.x() += 2.0 * half.x() + kGap;
        rowDepth = std::max(rowDepth, 2.0 * half.y());
        layerHeight = std::max(layerHeight, 2.0 * half.z());
    }
    boxSize = boxMax + Vec3::Constant(kGap);
    addWalls(scene, Vec3::Zero(), boxSize);
    return scene;
}

/// The tile after settling in its box (made once per process): grains with their poses and
/// velocities, and the box.
struct Tile
{
    std::vector<GrainSpec> grains;
    Vec3 boxSize = Vec3::Zero();
};

const Tile& settledTile()
{
    static const Tile tile = [] {
        Tile t;
        std::vector<std::string> warnings;
        World world = buildWorld(looseTile(t.boxSize), warnings);
        // Gravity raised while the tile settles, so its layers close their gaps in thousands
        // of steps rather than tens of thousands; the timed runs use plain gravity.
        const Vec3 gravity = world.gravity;
        world.gravity = kSettlingGravityFactor * gravity;
        const double dt = automaticTimeStep(world, 0.2);
        Simulation sim(std::move(world), dt);
        for (long long s = 0; s < kTileSettleSteps; ++s) sim.step();
        for (const Grain& grain : sim.world().grains) {
            GrainSpec g;
            g.asset = static_cast<int>(std::find(sandAssets().begin(), sandAssets().end(),
                                                 grain.asset) -
                                       sandAssets().begin());
            g.pose = grain.body.pose;
            g.velocity = grain.body.velocity;
            g.angularVelocity = grain.body.angularVelocity();
            t.grains.push_back(g);
        }
        return t;
    }();
    return tile;
}

/// Tiles side by side in x and y: as square a footprint as @a tiles allows.
Eigen::Vector2i tileLayout(int tiles)
{
    int across = static_cast<int>(std::sqrt(double(tiles)));
    while (tiles % across != 0) --across;
    return {tiles / across, across};
}

/// @a grains (a multiple of the tile's) as settled tiles side by side in one box of walls.
Scene sandBoxScene(int grains)
{
    Scene scene = sandScene();
    const Tile& tile = settledTile();
    const Eigen::Vector2i layout = tileLayout(grains / kTile.prod());
    for (int tx = 0; tx < layout.x(); ++tx)
        for (int ty = 0; ty < layout.y(); ++ty)
            for (GrainSpec g : tile.grains) {
                g.pose.position += Vec3(tx * tile.boxSize.x(), ty * tile.boxSize.y(), 0.0);
                scene.grains.push_back(g);
            }
    addWalls(scene, Vec3::Zero(),
             Vec3(layout.x() * tile.boxSize.x(), layout.y() * tile.boxSize.y(), 0.0));
    return scene;
}

/// The state after the settling prefix, made once per grain count (the last one is kept).
const Settled& settled(int grains)
{
    static Settled kept;
    if (kept.grains == grains) return kept;
    kept = Settled();
    settledTile();  // the assets and the tile are made before the memory is measured
    malloc_trim(0);
    resetPeakRss();
    const double before = statusBytes("VmRSS") / 1024.0;
    std::vector<std::string> warnings;
    World world = buildWorld(sandBoxScene(grains), warnings);
    const double dt = automaticTimeStep(world, 0.2);
    kept.sim = std::make_unique<Simulation>(std::move(world), dt);
    for (long long s = 0; s < kPrefixSteps; ++s) kept.sim->step();
    kept.grains = grains;
    kept.peakMiB = statusBytes("VmHWM") / 1024.0 / 1024.0;
    malloc_trim(0);  // hand freed memory (the scene, the first contact list) back first
    kept.heldBytesPerGrain = (statusBytes("VmRSS") / 1024.0 - before) * 1024.0 / grains;
    return kept;
}

} // namespace lsdem::scalebench
