#include "studies/TriaxialCost.h"

#include "studies/RunSchedule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem {

namespace {

// A step's cost on this machine's cores, fitted to whole runs (consolidation and shearing) of
// 200 to 1000 sand grains at 431 to 4786 nodes a grain, 2026-11-29 (docs/triaxial.md#cost):
// a part per grain node (the narrow phase, most of it) and a part per grain beyond the first
// kFreeGrains (small samples cost less per grain than the linear part says: a fit, within
// -21 % to +17 % of each of the twelve runs).
constexpr double kSecondsPerGrainNodeStep = 3.95e-9;
constexpr double kSecondsPerGrainStep = 4.57e-6;
constexpr double kFreeGrains = 170.0;
/// One thread against two (the narrow phase scales by about 1.9 on this machine's 2 cores).
constexpr double kOneThreadOverTwo = 1.9;
/// The consolidation's steps besides the approach and the hold: the walls slowing into σ₃
/// (the runs above consolidated in 5400–7500 steps, one in 10,200).
constexpr long long kRampSteps = 1200;

// In a membrane (fitted to 300 and 1000 grains at 431 nodes, 2026-11-29, after the membrane's
// contact kept candidate nodes; docs/triaxial.md#cost):
/// the cost of a node of a grain next to the membrane, tested against its triangles, beyond
/// the grain's own contacts: their shearing took 2.61 and 6.30 ms a step, the grain model
/// 0.22 and 2.62; 55 ns a node is the least-squares fit of the relative error of both.
constexpr double kSecondsPerMembraneNodeStep = 5.5e-8;
/// the consolidation in the membrane (its closing in, then the hold): 3000 and 5500 steps;
constexpr long long kMembraneConsolidationSteps = 4300, kMembraneConsolidationSpread = 1200;
/// the cylinder cut from a sample N grains wide (s = (N / height ratio)^(1/3) grains
/// across): its radius in mean diameters 0.583·s − 1.12 (2.78 and 4.71 measured), and the
/// grains it keeps N·π/4·(1 − 1.7/s)² (0.42, 0.455 and 0.541 of 300, 400 and 1000 measured).
constexpr double kRadiusPerWidth = 0.583, kRadiusLoss = 1.12, kKeptLoss = 1.7;

} // namespace

namespace {

/// Seconds on @a threads threads of what takes @a twoThreads on two.
double onThreads(double twoThreads, int threads)
{
    const double oneThread = kOneThreadOverTwo * twoThreads;
    // Beyond two: the same share of each added thread as the second gives.
    return threads <= 1 ? oneThread : oneThread / (1.0 + (kOneThreadOverTwo - 1.0) * (threads - 1));
}

} // namespace

double triaxialStepSeconds(double grains, double nodesPerGrain, int threads)
{
    return onThreads(grains * nodesPerGrain * kSecondsPerGrainNodeStep +
                         std::max(0.0, grains - kFreeGrains) * kSecondsPerGrainStep,
                     threads);
}

double membraneStepSeconds(double grains, double grainsAtMembrane, double nodesPerGrain,
                           int threads)
{
    return triaxialStepSeconds(grains, nodesPerGrain, threads) +
           onThreads(grainsAtMembrane * nodesPerGrain * kSecondsPerMembraneNodeStep, threads);
}

TriaxialRunCost triaxialRunCost(const TriaxialRunPlan& plan, int threads)
{
    TriaxialRunCost c;
    // The walls close at approachRate × the starting size until the cloud is dense: from the
    // cloud's void ratio to the consolidated one, each size shrinks by the cube root.
    const double shrink =
        1.0 - std::cbrt((1.0 + kConsolidatedVoidRatio) / (1.0 + std::max(plan.startVoidRatio,
                                                                          kConsolidatedVoidRatio)));
    const double approach = shrink / (plan.approachRate * plan.timeStep);
    c.consolidationSteps = static_cast<long long>(std::ceil(approach)) + kRampSteps + plan.settledSteps;
    c.shearSteps = plan.shearSteps;
    const double step = triaxialStepSeconds(double(plan.grains), plan.nodesPerGrain, threads);
    if (!plan.membrane) {
        c.seconds = double(c.consolidationSteps + c.shearSteps) * step;
        c.secondsAtMost = c.seconds + double(2 * plan.settledSteps) * step;
        return c;
    }
    // The walls' consolidation of the whole sample, then the cylinder's in the membrane and
    // its shearing.
    const double across = std::cbrt(double(plan.grains) / std::max(plan.heightRatio, 1e-9));
    const double radius = std::max(1.0, kRadiusPerWidth * across - kRadiusLoss);
    const double keptShare = std::max(0.0, 1.0 - kKeptLoss / across);
    c.keptGrains = double(plan.grains) * 0.25 * 3.14159265358979 * keptShare * keptShare;
    const double inner = 1.0 - 1.0 / radius;  // grains within a diameter of the membrane
    c.grainsAtMembrane = c.keptGrains * (1.0 - inner * inner);
    const double membraneStep =
        membraneStepSeconds(c.keptGrains, c.grainsAtMembrane, plan.nodesPerGrain, threads);
    c.membraneSteps = kMembraneConsolidationSteps;
    const double walls = double(c.consolidationSteps) * step;
    c.consolidationSteps += c.membraneSteps;
    c.seconds = walls + double(c.membraneSteps + c.shearSteps) * membraneStep;
    c.secondsAtMost = c.seconds + double(2 * plan.settledSteps) * step +
                      double(kMembraneConsolidationSpread + 2 * c.shearSteps) * membraneStep;
    return c;
}

std::string describeTriaxialCost(const std::vector<TriaxialRunPlan>& plans, int threads,
                                 int ranks)
{
    std::string text = "estimate (this machine's speed, +-30 %; a step halved on the way adds to it):\n";
    char line[200];
    std::snprintf(line, sizeof line, "  %-28s %7s %8s %10s %8s %12s\n", "run", "nodes", "dt [s]",
                  "consol.", "shear", "minutes");
    text += line;
    std::vector<double> seconds, most;
    double total = 0.0, totalAtMost = 0.0;
    for (const TriaxialRunPlan& p : plans) {
        const TriaxialRunCost c = triaxialRunCost(p, threads);
        std::snprintf(line, sizeof line, "  %-28s %7.0f %8.3g %10lld %8lld %5.2f-%.2f\n",
                      p.name.c_str(), p.nodesPerGrain, p.timeStep, c.consolidationSteps,
                      c.shearSteps, c.seconds / 60.0, c.secondsAtMost / 60.0);
        text += line;
        seconds.push_back(c.seconds);
        most.push_back(c.secondsAtMost);
        total += c.seconds;
        totalAtMost += c.secondsAtMost;
    }
    std::snprintf(line, sizeof line, "  in all about %.1f to %.1f min on %d thread%s",
                  total / 60.0, totalAtMost / 60.0, threads, threads == 1 ? "" : "s");
    text += line;
    if (ranks > 1) {
        std::snprintf(line, sizeof line, "; on %d ranks, largest runs first: about %.1f to %.1f min",
                      ranks, largestFirstMakespan(seconds, ranks) / 60.0,
                      largestFirstMakespan(most, ranks) / 60.0);
        text += line;
    }
    return text + "\n";
}

} // namespace lsdem
