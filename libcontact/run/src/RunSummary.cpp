#include "RunSummary.h"

#include <cstdio>
#include <ostream>

namespace lsdem {

void printRunSummary(std::ostream& log, const RunResult& r)
{
    const StepCounters& c = r.counters;
    const double stepping = c.broadSeconds + c.narrowSeconds + c.integrateSeconds +
                            r.decomposition.exchangeSeconds + r.decomposition.packSeconds;
    char line[200];
    log << "\nwhere the time went:\n";
    auto row = [&](const char* name, double s) {
        std::snprintf(line, sizeof line, "  %-22s %10.3f s  %5.1f %%\n", name, s,
                      r.wallSeconds > 0 ? 100.0 * s / r.wallSeconds : 0.0);
        log << line;
    };
    row("setup (assets, scene)", r.setupSeconds);
    row("broad phase", c.broadSeconds);
    row("narrow phase + laws", c.narrowSeconds);
    row("integration", c.integrateSeconds);
    const GhostCounters& d = r.decomposition;
    if (r.ranks > 1) {
        row("exchange", d.exchangeSeconds);
        row("exchange (pack)", d.packSeconds);
    }
    row("output", r.outputSeconds);
    row("total (wall)", r.wallSeconds);
    const double steps = static_cast<double>(c.steps);
    std::snprintf(line, sizeof line,
                  "throughput: %lld steps, %.3g ms/step, %.3g grain-steps/s, %.3g node checks/s "
                  "(%.1f %% culled before sampling)\n",
                  c.steps, steps > 0 ? 1e3 * stepping / steps : 0.0,
                  stepping > 0 ? steps * r.grains / stepping : 0.0,
                  c.narrowSeconds > 0 ? c.nodes.nodesConsidered / c.narrowSeconds : 0.0,
                  c.nodes.nodesConsidered > 0
                      ? 100.0 * double(c.nodes.nodesCulled) / double(c.nodes.nodesConsidered)
                      : 0.0);
    log << line;
    if (r.ranks > 1 && c.steps > 0) {
        const double perStep = 1.0 / steps;
        char split[600];
        std::snprintf(split, sizeof split,
                      "split over %d ranks (rank 0's figures): sent %.3g bytes and received %.3g "
                      "per step, %.1f %% of the step time exchanging; %d grains owned and %d "
                      "ghosts at the end, %lld grains migrated in and %lld out, %lld redraws of "
                      "the sub-domains, work max/mean %.3g at the last\n",
                      r.ranks, double(d.bytesSent) * perStep, double(d.bytesReceived) * perStep,
                      stepping > 0 ? 100.0 * (d.exchangeSeconds + d.packSeconds) / stepping : 0.0,
                      d.owned, d.ghosts, d.grainsMigrated, d.grainsEmigrated, d.rebalances,
                      d.lastImbalance);
        log << split;
    }
}

} // namespace lsdem
