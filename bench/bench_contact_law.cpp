// The contact law alone (resolveContact), without the narrow phase that finds the contacts: a
// flat face of node contacts pressed into a neighbour, as the slab's blocks are, with the
// adapted law, shear springs, friction and a dashpot. One iteration is one step of the contact:
// its shear history is carried to the next. Its working set is a few hundred KiB, so the
// figure is the law's arithmetic rather than the host's memory (issue 35: "the normal law,
// dashpot and shear springs over batches of nodes"). Args: nodes in contact (3: a contact of a
// few nodes, as between two spheres of a packing, which goes spring by spring); regime 0 = the
// face sticks (the slip reverses every step, so no spring reaches Coulomb's cap), 1 = it
// slides (a steady slip far past the cap).
#include "lsdem/contact/ContactLaw.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

using namespace lsdem;

namespace {

/// A square face of @a count nodes at z = 0, pressed 0.01–0.03 into the other body (slightly
/// tilted normals, uneven areas: a baked face's nodes are not a perfect lattice).
std::vector<NodeContact> pressedFace(int count)
{
    std::mt19937 random(3);
    std::uniform_real_distribution<double> jitter(-1.0, 1.0);
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    std::vector<NodeContact> face;
    for (int i = 0; i < count; ++i) {
        NodeContact c;
        c.node = i;
        c.depth = 0.02 + 0.01 * jitter(random);
        c.normal = Vec3(0.02 * jitter(random), 0.02 * jitter(random), 1.0).normalized();
        const Vec3 surface(0.1 * (i % side), 0.1 * (i / side), 0.0);
        c.point = surface + 0.5 * c.depth * c.normal;
        c.area = 0.01 * (1.0 + 0.1 * jitter(random));
        face.push_back(c);
    }
    return face;
}

void BM_ContactLaw(benchmark::State& state)
{
    const int count = static_cast<int>(state.range(0));
    const bool sliding = state.range(1) == 1;
    ContactModel model;
    model.formulation = Formulation::Adapted;
    model.normalStiffness = 1e3;
    model.shearStiffness = 0.5e3;
    model.friction = 0.5;
    model.damping = ViscousDamping(0.5);
    ContactGrain lower, upper;
    lower.pose.position = Vec3(1.0, 1.0, -1.0);
    lower.mass = 1e-3;
    upper.pose.position = Vec3(1.0, 1.0, 1.0);
    upper.mass = 1e-3;
    upper.index = 1;
    upper.velocity = Vec3::Zero();
    ContactSide side;
    side.tester = &upper;
    side.other = &lower;
    side.contacts = pressedFace(count);
    ShearHistory history;
    side.history = &history;
    ContactScratch scratch;
    // A node's spring takes ks*·A ≈ 5 per unit of slip and caps at μ·kn*·A·d ≈ 0.1. Sliding:
    // 0.1 of slip a step, five times the cap. Sticking: 1e-6 a step, back and forth.
    const double dt = 1e-3;
    const double speed = sliding ? 100.0 : 1e-3;
    long long step = 0;
    double sum = 0.0;
    for (auto _ : state) {
        const double sign = sliding || step % 2 == 0 ? 1.0 : -1.0;
        upper.velocity.x() = sign * speed;
        // Sliding, it twists about the face's normal too. (A twist back and forth would turn
        // the sticking springs a little more each way, and over millions of steps they would
        // creep to the cap.)
        upper.angularVelocity.z() = sliding ? 0.3 : 0.0;
        const PairForces r = resolveContact(&side, 1, model, dt, nullptr, &scratch);
        sum += r.forceOnFirst.x();
        ++step;
    }
    benchmark::DoNotOptimize(sum);
    state.counters["ns/contact"] = benchmark::Counter(
        static_cast<double>(state.iterations()) * count,
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    // How many springs are at their cap now (the regime is what its name says).
    int capped = 0;
    for (const ShearHistory::Entry& e : history.entries()) {
        const NodeContact& c = side.contacts[static_cast<size_t>(e.node)];
        const double limit = model.friction * model.normalStiffness * c.area * c.depth;
        capped += e.force.norm() > 0.99 * limit;
    }
    state.counters["sliding_nodes"] = capped;
}

} // namespace

BENCHMARK(BM_ContactLaw)
    ->ArgsProduct({{3, 6, 12, 24, 64, 2048}, {0, 1}})
    ->ArgNames({"contacts", "sliding"})
    ->Unit(benchmark::kMicrosecond);
