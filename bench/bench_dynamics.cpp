// Step time of the dynamics (issue: 1000 spheres settling in a box). Run:
//   build/bench/bench_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//       --benchmark_enable_random_interleaving=true   (one command line)
// (interleaved: the 1- and 2-thread repetitions alternate, so the host's drift over the minute
// the run takes falls on both and their ratio holds; run one after the other, it does not.)
// 1000 equal spheres (R = 5 mm, ~1000 nodes each, voxels R/10) in a 10×10×10 stack with
// slight random overlaps, in a box of walls, under gravity with damping: every grain has
// about six touching neighbours, so the ~3000 near pairs all carry contact. One iteration is
// one time step. Args: threads, node testing (0 one-way, 1 symmetric).

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <benchmark/benchmark.h>

#include <tbb/global_control.h>

#include <random>

using namespace lsdem;

namespace {

constexpr double kRadius = 5.0;
constexpr int kPerSide = 10;

Scene settlingScene(NodeTesting testing)
{
    Scene scene;
    AssetSpec sphere;
    sphere.name = "sphere";
    sphere.shape = AnalyticShape::sphere(kRadius);
    sphere.bake.voxelSize = kRadius / 10;
    sphere.bake.nodePlacement = NodePlacement::Count;
    sphere.bake.nodeCount = 1000;
    scene.assets.push_back(sphere);
    scene.materials = {{"grain", 2.6e-9}, {"wall", 0.0}};
    ContactModel model;
    model.formulation = Formulation::Adapted;
    model.testing = testing;
    model.normalStiffness = 1e3;   // N/mm³
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
    // Centres 1.99 R apart with ±0.005 R jitter: slight overlaps, so all neighbours touch.
    std::mt19937_64 random(7);
    auto jitter = [&] { return (double(random() >> 11) * 0x1.0p-53 - 0.5) * 0.01 * kRadius; };
    const double spacing = 1.99 * kRadius;
    for (int k = 0; k < kPerSide; ++k)
        for (int j = 0; j < kPerSide; ++j)
            for (int i = 0; i < kPerSide; ++i) {
                GrainSpec g;
                g.pose.position = Vec3(i * spacing + jitter(), j * spacing + jitter(),
                                       k * spacing + jitter());
                scene.grains.push_back(g);
            }
    // Walls touching the outer grains: floor, four sides.
    const double lo = -kRadius, hi = (kPerSide - 1) * spacing + kRadius;
    const Vec3 normals[5] = {Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                             -Vec3::UnitY()};
    const Vec3 points[5] = {Vec3(0, 0, lo), Vec3(lo, 0, 0), Vec3(hi, 0, 0), Vec3(0, lo, 0),
                            Vec3(0, hi, 0)};
    for (int w = 0; w < 5; ++w) {
        BoundarySpec b;
        b.name = "wall" + std::to_string(w);
        b.material = 1;
        b.point = points[w];
        b.normal = normals[w];
        scene.boundaries.push_back(b);
    }
    scene.gravity = Vec3(0, 0, -9810.0);  // mm/s²
    scene.globalDamping = 0.3;
    return scene;
}

void BM_SettlingStep(benchmark::State& state)
{
    const int threads = static_cast<int>(state.range(0));
    const NodeTesting testing = state.range(1) ? NodeTesting::Symmetric : NodeTesting::OneWay;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<std::string> warnings;
    World world = buildWorld(settlingScene(testing), warnings);
    // Explicit step: a fifth of the limit for a grain pressed by ~six adapted contacts.
    const double dt = 2e-6;
    Simulation sim(std::move(world), dt);
    for (int s = 0; s < 20; ++s) sim.step();  // warm up: contacts and histories exist
    const StepCounters before = sim.counters();
    for (auto _ : state) sim.step();
    const StepCounters& after = sim.counters();
    const double steps = double(after.steps - before.steps);
    state.counters["pairs/step"] = double(after.candidatePairs - before.candidatePairs) / steps;
    state.counters["nodes_checked/step"] =
        double(after.nodes.nodesConsidered - before.nodes.nodesConsidered) / steps;
    state.counters["nodes_sampled/step"] =
        double(after.nodes.nodesSampled - before.nodes.nodesSampled) / steps;
    state.counters["contact_nodes"] = double(sim.contactNodes());
    state.counters["broad_ms/step"] = 1e3 * (after.broadSeconds - before.broadSeconds) / steps;
    state.counters["narrow_ms/step"] = 1e3 * (after.narrowSeconds - before.narrowSeconds) / steps;
    state.counters["integrate_ms/step"] =
        1e3 * (after.integrateSeconds - before.integrateSeconds) / steps;
    state.counters["grain_steps/s"] =
        benchmark::Counter(1000.0 * steps, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SettlingStep)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->ArgNames({"threads", "symmetric"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(50);

} // namespace

BENCHMARK_MAIN();
