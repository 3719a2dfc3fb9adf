// Step time of the interlocked slab (issue: flat, face-to-face contacts, the expensive case).
// Run:
//   build/bench/bench_slab --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The study's 5×5 panel (adapted, symmetric node testing) with its block baked at three
// discretizations: the quick study's finest (fine:0, SDP 0.25 mm, VDP 0.05 mm, ~4,100 nodes
// per block), --full's finest (fine:1, SDP 0.125 mm, VDP 0.035 mm, ~16,500 nodes per block)
// and the paper's seed resolution (fine:2, SDP 0.06 mm, VDP 0.025 mm, ~74,500 nodes per
// block; its bake and preload take minutes and ~1 GB: leave it out with
// --benchmark_filter='fine:[01]'). Before timing, the indenter is driven to δ = 0.5 mm, so
// every face carries load; one iteration is one time step from there. Args: discretization,
// threads.

#include "studies/SlabModel.h"
#include "studies/SlabOptions.h"
#include "studies/SlabScene.h"

#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <benchmark/benchmark.h>

#include <tbb/global_control.h>

#include <map>
#include <memory>

using namespace lsdem;

namespace {

struct Discretization
{
    double sdp, vdp;
};
constexpr Discretization kDiscretizations[] = {{0.25, 0.05}, {0.125, 0.035}, {0.06, 0.025}};
constexpr double kPreloadDelta = 0.5;  // mm

/// The loaded panel of a discretization, made once: baking a fine block takes seconds to minutes.
const Simulation& loadedPanel(int which)
{
    static std::map<int, std::unique_ptr<Simulation>> made;
    std::unique_ptr<Simulation>& sim = made[which];
    if (!sim) {
        const SlabStudyOptions o;
        const SlabPanel panel(o.panel);
        const Discretization d = kDiscretizations[which];
        const auto block = bakeSlabBlock(panel, d.vdp, d.sdp);
        const double dt = slabTimeStep(o, panel, *block, Formulation::Adapted);
        std::vector<std::string> warnings;
        World world = buildWorld(makeSlabScene(o, Formulation::Adapted, block, dt), warnings);
        sim = std::make_unique<Simulation>(std::move(world), dt);
        const Boundary& indenter = sim->world().boundaries.back();
        while (-indenter.displacement.z() < kPreloadDelta) sim->step();
    }
    return *sim;
}

void BM_SlabStep(benchmark::State& state)
{
    const int which = static_cast<int>(state.range(0));
    const Simulation& loaded = loadedPanel(which);
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                static_cast<size_t>(state.range(1)));
    Simulation sim = loaded;  // every repetition steps on from the same loaded state
    const StepCounters before = sim.counters();
    for (auto _ : state) sim.step();
    const StepCounters& after = sim.counters();
    const double steps = static_cast<double>(after.steps - before.steps);
    const World& w = sim.world();
    double nodes = 0.0;
    for (const Grain& g : w.grains) nodes += static_cast<double>(g.asset->nodes.size());
    state.counters["sdp_mm"] = kDiscretizations[which].sdp;
    state.counters["nodes_per_block"] = nodes / static_cast<double>(w.grains.size());
    // The block's level set as held in memory (one asset, shared by the 25 blocks), and the
    // shares of its bricks stored deep and on a plane (16 bits a value, LevelSetBricks.h).
    const LevelSetBricks& grid = *w.grains.front().asset->levelSet->grid;
    state.counters["block_grid_MiB"] = static_cast<double>(grid.memUsage()) / (1024.0 * 1024.0);
    state.counters["bricks"] = static_cast<double>(grid.brickCount());
    state.counters["deep_bricks"] = static_cast<double>(grid.deepBrickCount());
    state.counters["plane_bricks"] = static_cast<double>(grid.planeBrickCount());
    state.counters["nodes_sampled/step"] =
        static_cast<double>(after.nodes.nodesSampled - before.nodes.nodesSampled) / steps;
    state.counters["contact_nodes"] = static_cast<double>(sim.contactNodes());
    state.counters["narrow_ms/step"] = 1e3 * (after.narrowSeconds - before.narrowSeconds) / steps;
    state.counters["ns/node_sampled"] =
        1e9 * (after.narrowSeconds - before.narrowSeconds) /
        static_cast<double>(after.nodes.nodesSampled - before.nodes.nodesSampled);
    // Remembered nodes passed over (sampled clear at an earlier step, unable to have reached
    // the other grain since; CandidateBlocks.h) were sampled every step before 2026-12-01:
    // per node sampled or passed over, the figure compares with the earlier ns/node_sampled.
    const double passedOver =
        static_cast<double>(after.nodes.nodesPassedOver - before.nodes.nodesPassedOver);
    state.counters["nodes_passed_over/step"] = passedOver / steps;
    state.counters["ns/node_sampled_or_passed_over"] =
        1e9 * (after.narrowSeconds - before.narrowSeconds) /
        (static_cast<double>(after.nodes.nodesSampled - before.nodes.nodesSampled) + passedOver);
}

/// The floor under a sampled node's cost (issue 35: "the physical limit"): the fine:1 block's
/// nodes, moved 0.3 voxel inward as a neighbour's penetrating nodes sit, read in their stored
/// (Morton) order from the block's grid (12.7 MiB, larger than this machine's caches). Arg 0:
/// only the 8 corner values of each node's cell (the stream of 8-voxel fetches: table look-up,
/// brick, 3-byte codes); arg 1: the sampler's φ and ∇φ, as the narrow phase asks for them.
void BM_NodeFetchFloor(benchmark::State& state)
{
    const bool fullSample = state.range(0) == 1;
    const GrainAsset& block = *loadedPanel(1).world().grains.front().asset;
    const LevelSetGrid& levelSet = *block.levelSet;
    const LevelSetBricks& grid = *levelSet.grid;
    std::vector<Vec3> points;
    for (size_t i = 0; i < block.nodes.size(); ++i)
        points.push_back(block.nodes.positions[i] - 0.3 * levelSet.voxelSize * block.nodes.normals[i]);
    LevelSetSampler sampler(levelSet);
    const double inverseVoxel = 1.0 / levelSet.voxelSize;
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3& p : points) {
            if (fullSample) {
                const LevelSetSample s = sampler.sample(p);
                sum += s.phi + s.gradient.x();
                continue;
            }
            const Vec3 index = (p - levelSet.origin) * inverseVoxel;
            const openvdb::Coord base(int(std::floor(index.x())), int(std::floor(index.y())),
                                      int(std::floor(index.z())));
            for (int corner = 0; corner < 8; ++corner)
                sum += grid.value(base.offsetBy(corner & 1, (corner >> 1) & 1, corner >> 2));
        }
        benchmark::DoNotOptimize(sum);
    }
    state.counters["ns_per_node"] = benchmark::Counter(
        double(points.size()),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["grid_MiB"] = double(grid.memUsage()) / (1024.0 * 1024.0);
}

/// This machine's streaming read bandwidth (a 256 MiB array summed in order), for the bytes
/// a node's fetch cannot avoid when its bricks are not in cache.
void BM_ReadBandwidth(benchmark::State& state)
{
    std::vector<double> data(size_t(32) << 20, 1.0);  // 256 MiB
    for (auto _ : state) {
        double sum = 0.0;
        for (double v : data) sum += v;
        benchmark::DoNotOptimize(sum);
    }
    state.counters["GB_per_s"] = benchmark::Counter(
        double(data.size() * sizeof(double)) / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

} // namespace

BENCHMARK(BM_NodeFetchFloor)->ArgName("full_sample")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadBandwidth)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_SlabStep)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->ArgNames({"fine", "threads"})
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
