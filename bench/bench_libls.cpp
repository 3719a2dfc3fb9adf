// Benchmarks for grain assets (issue: bake, memory, sampling). Run:
//   build/bench/bench_libls --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Medians are the figures to quote; this machine is shared and noisy. The bake benchmarks
// report wall time ("Time") and the CPU time of all threads ("CPU"); memory figures are
// resident bytes (/proc/self/status), so they include what malloc keeps but not what it gave
// back; a bake's figure starts after one small warm-up bake per process (warmUpProcess in
// MeshFamily.h), with the input mesh already resident. See docs/assets.md, "Cost".

#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/ls/MeshLevelSet.h"

#include "MeshFamily.h"
#include "ProcessMemory.h"

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

using namespace lsdem;
using namespace lsdem::bench;

namespace {

const GrainAsset& sphereAsset()
{
    static const GrainAsset asset = [] {
        BakeOptions o;
        o.voxelSize = 0.05;  // R/100
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 16000;
        std::vector<std::string> warnings;
        return bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings);
    }();
    return asset;
}


/// The 100k-triangle pebble in its principal frame, as bakeMesh has it before the stages.
const TriangleMesh& framedPebble()
{
    static const TriangleMesh mesh = [] {
        TriangleMesh m = familyMesh(0).mesh;  // the pebble, 100,820 triangles
        const PrincipalFrame frame = principalFrame(computeMassProperties(m), m);
        transformMesh(m, frame.rotation, -(frame.rotation * frame.centroid));
        return m;
    }();
    return mesh;
}

/// The whole bake; peak_over_grid is the resident high-water mark while baking, above what
/// was resident before, over the final grid's own memory.
void BM_BakeMesh100kTriangles(benchmark::State& state)
{
    const TriangleMesh mesh = familyMesh(0).mesh;  // the pebble, 100,820 triangles
    const BakeOptions o = familyBakeOptions();
    size_t nodes = 0;
    double peak = 0, grid = 0;
    for (auto _ : state) {
        std::vector<std::string> warnings;
        TriangleMesh input = mesh;  // the input, resident before as a reader leaves it
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        const GrainAsset asset = bakeMesh(std::move(input), "pebble", o, warnings);
        peak = statusBytes("VmHWM") - before;
        grid = double(asset.levelSet->grid->memUsage());
        nodes = asset.nodes.size();
        benchmark::DoNotOptimize(asset.levelSet.get());
    }
    state.counters["triangles"] = double(mesh.triangles.size());
    state.counters["nodes"] = double(nodes);
    state.counters["grid_MiB"] = grid / kMiB;
    state.counters["peak_MiB"] = peak / kMiB;
    state.counters["peak_over_grid"] = peak / grid;
}
BENCHMARK(BM_BakeMesh100kTriangles)->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

// The stages of that bake, one at a time, on the same mesh already in its principal frame.

void BM_BakeStageMass(benchmark::State& state)
{
    const TriangleMesh mesh = familyMesh(0).mesh;
    for (auto _ : state) {
        const MassProperties props = computeMassProperties(mesh);
        const PrincipalFrame frame = principalFrame(props, mesh);
        benchmark::DoNotOptimize(frame.moments);
    }
}
BENCHMARK(BM_BakeStageMass)->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

/// A 48-bit FNV-1a hash of every voxel's value and state (exact in a double counter): a
/// change to the level-set code that should not change the grid must leave it as it was.
double gridHash(const LevelSetBricks& grid)
{
    uint64_t h = 14695981039346656037ull;
    auto mix = [&h](uint64_t word) { h = (h ^ word) * 1099511628211ull; };
    auto bits = [](float v) {
        uint32_t b = 0;
        std::memcpy(&b, &v, sizeof b);
        return uint64_t(b);
    };
    auto voxel = [&](const openvdb::Coord& c, float v, bool on) {
        for (int k = 0; k < 3; ++k) mix(uint64_t(uint32_t(c[k])));
        mix(bits(v));
        mix(on ? 1u : 0u);
    };
    grid.forEachBrick(voxel, [&](const openvdb::CoordBBox& box, float v, bool on) {
        voxel(box.min(), v, on);  // a brick of one value: its corner stands for it
    });
    return double(h >> 16);
}

void BM_BakeStageLevelSet(benchmark::State& state)
{
    const TriangleMesh& mesh = framedPebble();
    const BakeOptions o = familyBakeOptions();
    double peak = 0, grid = 0, active = 0, hash = 0;
    for (auto _ : state) {
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        const auto levelSet = meshLevelSet(mesh, o.voxelSize, o.exteriorBandVoxels);
        peak = statusBytes("VmHWM") - before;
        grid = double(levelSet->grid->memUsage());
        active = double(levelSet->grid->activeVoxelCount());
        state.PauseTiming();  // the hash is for checking, not part of the stage
        hash = gridHash(*levelSet->grid);
        state.ResumeTiming();
    }
    state.counters["grid_MiB"] = grid / kMiB;
    state.counters["peak_MiB"] = peak / kMiB;
    state.counters["peak_over_grid"] = peak / grid;
    state.counters["active_voxels"] = active;
    state.counters["grid_hash"] = hash;
}
BENCHMARK(BM_BakeStageLevelSet)->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

void BM_BakeStageRemesh(benchmark::State& state)
{
    const TriangleMesh& mesh = framedPebble();
    const BakeOptions o = familyBakeOptions();
    size_t vertices = 0;
    double peak = 0;
    for (auto _ : state) {
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        vertices = nodeSurface(mesh, o, true).vertices.size();
        peak = statusBytes("VmHWM") - before;
    }
    state.counters["nodes"] = double(vertices);
    state.counters["peak_MiB"] = peak / kMiB;
}
BENCHMARK(BM_BakeStageRemesh)->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

void BM_BakeStageAreas(benchmark::State& state)
{
    const TriangleMesh surface = nodeSurface(framedPebble(), familyBakeOptions(), true);
    for (auto _ : state) {
        SurfaceNodes nodes = nodesFromMesh(surface, AreaRule::Mesh);
        sortNodesSpatially(nodes, 0.05);
        benchmark::DoNotOptimize(groupNodesIntoBlocks(nodes));
        benchmark::DoNotOptimize(nodeSpacing(nodes).mean);
    }
}
BENCHMARK(BM_BakeStageAreas)->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

/// The small grain: a 2×1×0.5 box at VDP 0.02, its grid against a dense float array
/// of the grid's active bounding box.
void BM_SmallBoxSparseVsDense(benchmark::State& state)
{
    BakeOptions o;
    o.voxelSize = 0.02;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = 0.05;
    double sparse = 0, dense = 0;
    for (auto _ : state) {
        std::vector<std::string> warnings;
        const GrainAsset asset = bakeAnalytic(AnalyticShape::box(2.0, 1.0, 0.5), o, warnings);
        const auto& grid = *asset.levelSet->grid;
        sparse = double(grid.memUsage());
        dense = 4.0 * double(grid.evalActiveVoxelBoundingBox().volume());
    }
    state.counters["sparse_MiB"] = sparse / kMiB;
    state.counters["dense_MiB"] = dense / kMiB;
    state.counters["sparse_over_dense"] = sparse / dense;
}
BENCHMARK(BM_SmallBoxSparseVsDense)->Unit(benchmark::kMillisecond)->Iterations(1);

/// A sphere-like pebble of radius 1 with its own bumps (seed), about 5,000 triangles.
TriangleMesh smallPebble(int seed)
{
    std::mt19937 random{uint32_t(seed)};
    std::uniform_real_distribution<double> phase(0.0, 6.283);
    const double a = phase(random), b = phase(random), c = phase(random);
    TriangleMesh mesh = AnalyticShape::sphere(1.0).surfaceMesh(1.05 / 16);
    for (Vec3& v : mesh.vertices) {
        const Vec3 u = v.normalized();
        v = u * (1.0 + 0.08 * std::sin(3 * u.x() + a) * std::cos(2 * u.y() + b) +
                 0.05 * std::sin(5 * u.z() + c));
    }
    return mesh;
}

/// The resident memory of 1000 distinct assets of sphere-like grains at VDP = R/20 with about
/// 1000 nodes each. Baking 1000 would take minutes, so 10 are baked (distinct bumps) and each
/// is deep-copied 100 times: every copy owns its grid and nodes, as a distinct asset would.
/// Arg: 0 whole, as baked or loaded; 1 as a simulation holds them, without the nodes' normals.
void BM_ThousandAssetsMemory(benchmark::State& state)
{
    const bool asSimulationHolds = state.range(0) == 1;
    BakeOptions o;
    o.voxelSize = 0.05;  // R/20
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = 1000;
    std::vector<GrainAsset> baked;
    for (int seed = 0; seed < 10; ++seed) {
        std::vector<std::string> warnings;
        baked.push_back(bakeMesh(smallPebble(seed), "pebble", o, warnings));
    }
    double resident = 0, grids = 0, nodes = 0, bricks = 0, deepBricks = 0, planeBricks = 0,
           narrowBricks = 0;
    for (auto _ : state) {
        malloc_trim(0);
        const double before = statusBytes("VmRSS");
        std::vector<GrainAsset> assets;
        assets.reserve(1000);
        grids = bricks = deepBricks = planeBricks = narrowBricks = 0;
        for (int i = 0; i < 1000; ++i) {
            GrainAsset copy = baked[size_t(i % 10)];
            if (asSimulationHolds) copy.nodes.dropNormals();
            auto levelSet = std::make_shared<LevelSetGrid>(*copy.levelSet);
            levelSet->grid = std::make_shared<const LevelSetBricks>(*levelSet->grid);
            grids += double(levelSet->grid->memUsage());
            bricks += double(levelSet->grid->brickCount());
            deepBricks += double(levelSet->grid->deepBrickCount());
            planeBricks += double(levelSet->grid->planeBrickCount());
            narrowBricks += double(levelSet->grid->narrowBrickCount());
            copy.levelSet = levelSet;
            assets.push_back(std::move(copy));
        }
        resident = statusBytes("VmRSS") - before;
        nodes = double(assets[0].nodes.size());
        benchmark::DoNotOptimize(assets.data());
    }
    state.counters["resident_MiB"] = resident / kMiB;
    state.counters["grids_MiB"] = grids / kMiB;
    state.counters["KiB_per_asset"] = resident / 1000.0 / 1024.0;
    state.counters["nodes_per_asset"] = nodes;
    state.counters["bricks_per_asset"] = bricks / 1000.0;
    state.counters["deep_bricks_per_asset"] = deepBricks / 1000.0;
    state.counters["plane_bricks_per_asset"] = planeBricks / 1000.0;
    state.counters["narrow_bricks_per_asset"] = narrowBricks / 1000.0;
}
BENCHMARK(BM_ThousandAssetsMemory)
    ->ArgName("in_simulation")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_AssetMemory(benchmark::State& state)
{
    const GrainAsset& asset = sphereAsset();
    const auto& grid = *asset.levelSet->grid;
    double sparse = 0, dense = 0;
    for (auto _ : state) {
        sparse = double(grid.memUsage());
        dense = 4.0 * double(grid.evalActiveVoxelBoundingBox().volume());
    }
    state.counters["sparse_MiB"] = sparse / (1024.0 * 1024.0);
    state.counters["dense_MiB"] = dense / (1024.0 * 1024.0);
    state.counters["sparse_over_dense"] = sparse / dense;
    state.counters["active_voxels"] = double(grid.activeVoxelCount());
    state.counters["bricks"] = double(grid.brickCount());
    state.counters["deep_bricks"] = double(grid.deepBrickCount());
    state.counters["plane_bricks"] = double(grid.planeBrickCount());
    state.counters["narrow_bricks"] = double(grid.narrowBrickCount());
}
BENCHMARK(BM_AssetMemory)->Iterations(1);

/// The slope bound that every bake and load derives (levelSetSlopeBound), on the R/100
/// sphere's grid (about the size of the 100k-triangle scan's): as the library finds it, window
/// by window over the bricks, against arg 1: the earlier bound (√3 times the largest step
/// between neighbours anywhere, until the seventh session of 2026-11-27) voxel by voxel, four
/// look-ups per voxel over the whole table, in parallel by x (how it was found until earlier
/// that day): a yardstick of cost, not of the same number.
void BM_SlopeBound(benchmark::State& state)
{
    const LevelSetGrid& levelSet = *sphereAsset().levelSet;
    const LevelSetBricks& grid = *levelSet.grid;
    double bound = 0.0;
    for (auto _ : state) {
        if (state.range(0) == 0) {
            bound = levelSetSlopeBound(levelSet);
        } else {
            const openvdb::CoordBBox table = grid.tableBox();
            const openvdb::Coord lo = table.min().offsetBy(-1), hi = table.max();
            const double largest = tbb::parallel_reduce(
                tbb::blocked_range<int>(lo.x(), hi.x() + 1), 0.0,
                [&](const tbb::blocked_range<int>& xs, double found) {
                    for (int x = xs.begin(); x != xs.end(); ++x)
                        for (int y = lo.y(); y <= hi.y(); ++y)
                            for (int z = lo.z(); z <= hi.z(); ++z) {
                                const openvdb::Coord c(x, y, z);
                                const double v = grid.value(c);
                                found = std::max(
                                    {found, std::abs(grid.value(c.offsetBy(1, 0, 0)) - v),
                                     std::abs(grid.value(c.offsetBy(0, 1, 0)) - v),
                                     std::abs(grid.value(c.offsetBy(0, 0, 1)) - v)});
                            }
                    return found;
                },
                [](double a, double b) { return std::max(a, b); });
            bound = std::sqrt(3.0) * largest / levelSet.voxelSize;
        }
        benchmark::DoNotOptimize(bound);
    }
    state.counters["bound"] = bound;
    state.counters["table_MVoxels"] = double(grid.tableBox().volume()) * 1e-6;
}
BENCHMARK(BM_SlopeBound)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

/// φ+∇φ at every node of the asset, offset slightly inward (as a penetrating node of a
/// neighbour would be), in the stored (Morton) order or shuffled.
void sampleNodes(benchmark::State& state, bool shuffled)
{
    const GrainAsset& asset = sphereAsset();
    std::vector<Vec3> points;
    for (size_t i = 0; i < asset.nodes.size(); ++i)
        points.push_back(asset.nodes.positions[i] - 0.01 * asset.nodes.normals[i]);
    if (shuffled) std::shuffle(points.begin(), points.end(), std::mt19937(42));
    LevelSetSampler sampler(*asset.levelSet);
    for (auto _ : state) {
        double sum = 0;
        for (const Vec3& p : points) {
            const LevelSetSample s = sampler.sample(p);
            sum += s.phi + s.gradient.x();
        }
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(points.size()));
    state.counters["ns_per_sample"] = benchmark::Counter(
        double(points.size()), benchmark::Counter::kIsIterationInvariantRate |
                                   benchmark::Counter::kInvert);
}

void BM_SampleNodesStoredOrder(benchmark::State& state) { sampleNodes(state, false); }
void BM_SampleNodesRandomOrder(benchmark::State& state) { sampleNodes(state, true); }
BENCHMARK(BM_SampleNodesStoredOrder);
BENCHMARK(BM_SampleNodesRandomOrder);

} // namespace

BENCHMARK_MAIN();
