// Step time and memory at scale (issue: 100,000 grains on one machine). Run:
//   build/bench/bench_scale --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (a filter such as --benchmark_filter='grains:10000/' runs one grain count).
//
// 1,000, 10,000 and 100,000 sand-like grains: ten ellipsoids of different semi-axes (volume-
// equivalent radius 0.4-0.6 mm, elongation and flatness 0.6-0.95, ~500 nodes and voxels of
// c/8 each; adapted formulation, symmetric testing, friction, restitution 0.5, global damping
// 0.3), settled under gravity in a box of walls (floor and four sides).
//
// Settling a heap from a loose packing takes ~10⁵ steps of ~1 µs, too many to repeat at
// 100,000 grains, so the heap is built from tiles: once per process a tile of 250 grains
// (5 × 5 × 10, randomly turned, packed by their bounding boxes 0.02 mm apart: a loose
// lattice) settles in its own box for 8,000 steps under 100 g; tiles of that settled state
// then stand side by side (2 × 2, 8 × 5, 20 × 20) in one box under plain gravity, and step
// kPrefixSteps more before anything is timed. That state is kept for its grain count; every
// repetition steps on from a copy of it (so all repetitions and thread counts time the same
// steps, and the copy's first step, which rebuilds its contact list, is not timed). One
// iteration is one time step; fewer iterations for more grains. Args: grains, threads.
//
// BM_ScaleStep counters: grain_steps/s; contacts (grain–grain and grain–wall pairs with a node
// in contact), contact nodes and pairs on the contact list, per grain; the phases' ms per step
// (wall clock); peak RSS while the state was built and settled (VmHWM, reset before each grain
// count); the resident memory the state holds per grain, and its shares from the sizes of the
// data structures. The CPU column is the process's CPU time (all threads): on a shared machine
// it is the steadier figure. BM_ListRebuild rebuilds the contact list alone;
// BM_StepAfterRebuild is a step that starts by rebuilding it from scratch.
// BM_LoadDistinctAssets times buildWorld loading 1000 asset files (ms_per_asset).
#include "ScaleHeap.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/simulation/Simulation.h"

#include <benchmark/benchmark.h>

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

using namespace lsdem;
using namespace lsdem::scalebench;

namespace {

/// Where the memory of a simulation goes, from the sizes of its parts: per grain (the grain,
/// its view for the contact laws, its stiffness, its position at the list build, its slot
/// index and stability limit) and per pair on the contact list (its slot, its two
/// per-grain references, its history map node), plus the shear histories' entries.
struct MemoryShares
{
    double perGrain = 0.0, perListPair = 0.0, historyBytes = 0.0;
};

MemoryShares memoryShares(const World& w)
{
    MemoryShares m;
    m.perGrain = double(sizeof(Grain) + sizeof(ContactGrain) + sizeof(Mat3) + sizeof(Vec3) +
                        sizeof(size_t) + sizeof(double));
    // A std::map node: the value and a red-black tree header (colour, parent, left, right).
    constexpr size_t kTreeNodeHeader = 32;
    m.perListPair = double(sizeof(ContactSlot) + 2 * sizeof(GrainSlotRef) +
                           sizeof(std::pair<const std::pair<int, int>, PairHistory>) +
                           kTreeNodeHeader);
    for (const auto& [pair, h] : w.pairHistory)
        m.historyBytes += double((h.shearOnFirstNodes.entries().capacity() +
                                  h.shearOnSecondNodes.entries().capacity()) *
                                 sizeof(ShearHistory::Entry));
    return m;
}

void BM_ScaleStep(benchmark::State& state)
{
    const int grains = static_cast<int>(state.range(0));
    const Settled& start = settled(grains);
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                static_cast<size_t>(state.range(1)));
    Simulation sim = *start.sim;
    sim.step();  // a copy rebuilds its contact list: not part of the timed steps
    const StepCounters before = sim.counters();
    for (auto _ : state) sim.step();
    const StepCounters& after = sim.counters();
    const double steps = static_cast<double>(after.steps - before.steps);
    const double n = static_cast<double>(grains);
    state.counters["grain_steps/s"] =
        benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
    state.counters["contacts/grain"] = contactsNow(sim.world()) / n;
    state.counters["contact_nodes/grain"] = static_cast<double>(sim.contactNodes()) / n;
    state.counters["nodes_sampled/grain"] =
        static_cast<double>(after.nodes.nodesSampled - before.nodes.nodesSampled) / steps / n;
    state.counters["list_pairs/grain"] =
        static_cast<double>(after.candidatePairs - before.candidatePairs) / steps / n;
    state.counters["rebuilds/step"] =
        static_cast<double>(after.listRebuilds - before.listRebuilds) / steps;
    state.counters["broad_ms/step"] = 1e3 * (after.broadSeconds - before.broadSeconds) / steps;
    state.counters["narrow_ms/step"] = 1e3 * (after.narrowSeconds - before.narrowSeconds) / steps;
    state.counters["integrate_ms/step"] =
        1e3 * (after.integrateSeconds - before.integrateSeconds) / steps;
    state.counters["peak_RSS_MiB"] = start.peakMiB;
    state.counters["held_B/grain"] = start.heldBytesPerGrain;
    const MemoryShares shares = memoryShares(sim.world());
    state.counters["struct_B/grain"] = shares.perGrain;
    state.counters["struct_B/list_pair"] = shares.perListPair;
    state.counters["history_B/grain"] = shares.historyBytes / n;
}

/// Rebuilding the contact list alone (broad phase, slots, histories, per-grain slot lists),
/// as the state after the prefix stands.
void BM_ListRebuild(benchmark::State& state)
{
    const int grains = static_cast<int>(state.range(0));
    World world = settled(grains).sim->world();
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                static_cast<size_t>(state.range(1)));
    ContactList list;
    list.update(world);
    for (auto _ : state) {
        list.markStale();
        list.update(world);
    }
    state.counters["list_pairs/grain"] = double(list.pairSlotCount()) / grains;
    state.counters["ns/grain"] = benchmark::Counter(
        1e-9 * grains * double(state.iterations()),
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// A step that starts with a rebuilt contact list (as when some grain has moved half the
/// skin): the rebuild and whatever the slots had to find again.
void BM_StepAfterRebuild(benchmark::State& state)
{
    const int grains = static_cast<int>(state.range(0));
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                static_cast<size_t>(state.range(1)));
    Simulation sim = *settled(grains).sim;
    sim.step();
    for (auto _ : state) {
        sim.invalidateContacts();
        sim.step();
    }
}

/// The ten sand-like assets saved as files, once per process, in a folder removed at exit.
const std::vector<std::string>& sandAssetFiles()
{
    struct Folder
    {
        std::filesystem::path path;
        std::vector<std::string> files;
        ~Folder() { std::filesystem::remove_all(path); }
    };
    static const Folder folder = [] {
        Folder f;
        std::string name = (std::filesystem::temp_directory_path() / "lsdem-bench-XXXXXX").string();
        if (!mkdtemp(name.data())) throw std::runtime_error("cannot make a folder in /tmp");
        f.path = name;
        for (size_t k = 0; k < sandAssets().size(); ++k) {
            f.files.push_back((f.path / ("sand" + std::to_string(k) + ".vdb")).string());
            saveAsset(*sandAssets()[k], f.files.back());
        }
        return f;
    }();
    return folder.files;
}

/// A scene of many distinct scanned grains starts by loading every asset: buildWorld on a
/// scene of 1000 assets from files (the ten sand-like ones, each loaded 100 times: as many
/// loads as 1000 distinct files). Args: threads.
void BM_LoadDistinctAssets(benchmark::State& state)
{
    constexpr int kAssets = 1000;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(state.range(0)));
    Scene scene = sandScene();
    scene.assets.clear();
    for (int k = 0; k < kAssets; ++k) {
        AssetSpec spec;
        spec.name = "scan" + std::to_string(k);
        spec.file = sandAssetFiles()[size_t(k % kAssetCount)];
        scene.assets.push_back(spec);
    }
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<std::string> warnings;
        const World w = buildWorld(scene, warnings);
        benchmark::DoNotOptimize(w.assets.data());
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    state.counters["ms_per_asset"] = 1e3 * seconds / double(state.iterations()) / kAssets;
}
BENCHMARK(BM_LoadDistinctAssets)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

// One grain count after the other (each settles its own state once); fewer steps for more
// grains: a repetition at 100,000 grains takes seconds.
void registerScale(int grains, int steps)
{
    // Every benchmark here: timed per step, wall clock and the whole process's CPU time.
    auto perStep = [steps](benchmark::internal::Benchmark* b) {
        b->ArgNames({"grains", "threads"})
            ->Iterations(steps)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MeasureProcessCPUTime();
    };
    perStep(benchmark::RegisterBenchmark("BM_ScaleStep", BM_ScaleStep)
                ->Args({grains, 1})
                ->Args({grains, 2}));
    perStep(benchmark::RegisterBenchmark("BM_StepAfterRebuild", BM_StepAfterRebuild)
                ->Args({grains, 2}));
    perStep(benchmark::RegisterBenchmark("BM_ListRebuild", BM_ListRebuild)->Args({grains, 2}));
}

} // namespace

int main(int argc, char** argv)
{
    registerScale(1000, 100);
    registerScale(10000, 20);
    registerScale(100000, 5);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
