#include "studies/verify/ImpactTrace.h"

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

ImpactTrace traceImpact(Simulation& sim, const std::function<double(const World&)>& overlap,
                        const std::function<double(const World&)>& force, long long maxSteps)
{
    ImpactTrace t;
    t.curve.columns = {"time", "overlap", "force"};
    long long first = -1, steps = 0;
    for (long long k = 0; k < maxSteps; ++k) {
        sim.step();
        const bool touching = sim.contactNodes() > 0;
        if (touching && first < 0) first = k;
        if (first < 0) continue;
        if (!touching) {
            t.ended = true;
            break;
        }
        ++steps;
        const double d = overlap(sim.world()), f = force(sim.world());
        t.maxOverlap = std::max(t.maxOverlap, d);
        t.peakForce = std::max(t.peakForce, f);
        t.curve.rows.push_back({double(k - first) * sim.timeStep(), d, f});
    }
    t.contactTime = double(steps) * sim.timeStep();
    return t;
}

} // namespace lsdem::verify
