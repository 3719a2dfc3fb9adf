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

} // namespace

double triaxialStepSeconds(long long grains, double nodesPerGrain, int threads)
{
    const double g = double(grains);
    const double twoThreads = g * nodesPerGrain * kSecondsPerGrainNodeStep +
                              std::max(0.0, g - kFreeGrains) * kSecondsPerGrainStep;
    const double oneThread = kOneThreadOverTwo * twoThreads;
    // Beyond two: the same share of each added thread as the second gives.
    return threads <= 1 ? oneThread : oneThread / (1.0 + (kOneThreadOverTwo - 1.0) * (threads - 1));
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
    const double step = triaxialStepSeconds(plan.grains, plan.nodesPerGrain, threads);
    c.seconds = double(c.consolidationSteps + c.shearSteps) * step;
    c.secondsAtMost = c.seconds + double(2 * plan.settledSteps) * step;
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
