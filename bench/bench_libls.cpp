// Benchmarks for grain assets (issue: bake, memory, sampling). Run:
//   build/bench/bench_libls --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Medians are the figures to quote; this machine is shared and noisy.

#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace lsdem;

namespace {

/// A bumpy closed "pebble" of about 20·n² triangles: an icosphere with smooth radial bumps, so
/// the mesh is not an analytic shape the code could shortcut.
TriangleMesh pebble(int subdivisionsPerEdge)
{
    // The sphere's surface mesh at edge ~1.05·R/n is an icosphere with 20·n² triangles.
    const double radius = 5.0;
    TriangleMesh mesh = AnalyticShape::sphere(radius).surfaceMesh(1.05 * radius / subdivisionsPerEdge);
    for (Vec3& v : mesh.vertices) {
        const Vec3 u = v.normalized();
        const double bump = 1.0 + 0.08 * std::sin(3 * u.x()) * std::cos(2 * u.y()) +
                            0.05 * std::sin(5 * u.z() + 1.0);
        v = u * radius * bump;
    }
    return mesh;
}

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

void BM_BakeMesh100kTriangles(benchmark::State& state)
{
    const TriangleMesh mesh = pebble(71);  // 100,820 triangles
    BakeOptions o;
    o.voxelSize = 0.05;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = 0.12;
    size_t nodes = 0;
    for (auto _ : state) {
        std::vector<std::string> warnings;
        const GrainAsset asset = bakeMesh(mesh, "pebble", o, warnings);
        nodes = asset.nodes.size();
        benchmark::DoNotOptimize(asset.levelSet.get());
    }
    state.counters["triangles"] = double(mesh.triangles.size());
    state.counters["nodes"] = double(nodes);
}
BENCHMARK(BM_BakeMesh100kTriangles)->Unit(benchmark::kMillisecond)->Iterations(1);

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
}
BENCHMARK(BM_AssetMemory)->Iterations(1);

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
