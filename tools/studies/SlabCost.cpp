#include "studies/SlabCost.h"

#include "studies/RunSchedule.h"
#include "studies/SlabModel.h"

#include "lsdem/mesh/MeshRemesh.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace lsdem {

namespace {

/// "a to b min" or "a min".
std::string minutes(double least, double most)
{
    std::ostringstream t;
    t << std::setprecision(3);
    if (least < 0.99 * most)
        t << least / 60.0 << " to " << most / 60.0 << " min";
    else
        t << most / 60.0 << " min";
    return t.str();
}

} // namespace

SlabRunCost slabRunCost(const SlabStudyOptions& o, const SlabCase& run)
{
    const SlabPanel panel(o.panel);
    const double area = surfaceArea(panel.referenceMesh());
    const double blocks = double(panel.n()) * panel.n();
    const SlabStiffness k = slabStiffness(o);
    const double mass = o.material.density * panel.blockVolume();
    // Measured on this machine (2 cores, see docs/slab.md): 16–18 ns of wall time per block
    // node and step when the cores are idle (bench_slab, from 4,132 to 74,528 nodes per block,
    // 2026-11-25), both directions of symmetric testing and the shear history included; 20 ns
    // leaves room for a little load.
    const double secondsPerNodeStep = 20e-9;
    SlabRunCost c;
    c.nodes = nodeCountForEdgeLength(area, run.sdp);  // a block remeshed at the SDP
    const ContactModel model = slabContactModel(o, run.formulation);
    const double face =
        model.normal().patchStiffness(model.normalStiffness, panel.sharedFaceArea(), area / c.nodes);
    const double dt =
        o.timeStepSafety * 2.0 * std::sqrt(mass / (2.0 * face * std::max(1.0, k.ksStar / k.knStar)));
    // Clamped before the cast: absurd inputs are refused by the caller, not undefined here.
    c.steps = static_cast<long long>(std::min(std::ceil(slabDeltaMax(o) / (o.speed * dt)), 1e15));
    c.seconds = c.steps * blocks * c.nodes * secondsPerNodeStep;
    // The peak is the bake: measured 816 MB resident for the block at VDP 0.025 mm (a
    // 58 MiB asset), about 48 bytes per voxel of the block's padded bounding box. Then
    // the run: nodes (position, normal, area) and the shear history per node in contact
    // (a std::map entry, ~80 bytes) for about half the nodes of every block.
    const double vdp = run.vdp;
    const double box = (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                       (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                       (o.panel.thickness + 10 * vdp);
    c.bytes = 48.0 * box / (vdp * vdp * vdp) + c.nodes * 56.0 + blocks * c.nodes * 0.5 * 80.0;
    return c;
}

double slabSecondsOnRanks(const SlabCostEstimate& e, int ranks, double coresPerRank, bool most)
{
    const double slowdown = 2.0 / std::max(coresPerRank, 1e-9);
    return slowdown * (largestFirstMakespan(e.stageOne, ranks) +
                       largestFirstMakespan(most ? e.stageTwoMost : e.stageTwoLeast, ranks));
}

SlabCostEstimate estimateSlabCost(const SlabStudyOptions& o, int ranks, double coresPerRank)
{
    SlabCostEstimate e;
    const double blocks = double(o.panel.blocksPerSide) * o.panel.blocksPerSide;
    // Counted runs: the upper bound's (stage 2 at the finest SDP).
    auto count = [&](const SlabRunCost& c) {
        ++e.runs;
        e.steps += c.steps;
        e.seconds += c.seconds;
        e.nodesPerBlockFinest = std::max(e.nodesPerBlockFinest, c.nodes);
        e.memoryBytes = std::max(e.memoryBytes, c.bytes);
    };
    for (const SlabCase& c : slabStageOneCases(o)) {
        const SlabRunCost cost = slabRunCost(o, c);
        count(cost);
        e.stageOne.push_back(cost.seconds);
    }
    e.secondsAtLeast = e.seconds;
    if (o.twoWay) {
        // Stage 2 runs at the converged SDP, not known yet: it costs least at the coarsest SDP
        // and most at the finest.
        const std::vector<double> sdps = slabCoarseToFine(o.sdps);
        const std::vector<SlabCase> most = slabStageTwoCases(o, sdps.back());
        const std::vector<SlabCase> least = slabStageTwoCases(o, sdps.front());
        for (size_t i = 0; i < most.size(); ++i) {
            if (std::abs(most[i].vdp - o.fixedVdp) <= 1e-12) continue;  // shared with stage 1
            const double leastSeconds = slabRunCost(o, least[i]).seconds;
            e.secondsAtLeast += leastSeconds;
            e.stageTwoLeast.push_back(leastSeconds);
            const SlabRunCost cost = slabRunCost(o, most[i]);
            count(cost);
            e.stageTwoMost.push_back(cost.seconds);
        }
        const SlabRunCost coarse = slabRunCost(o, slabCoarseCase(o));  // snapshots
        e.secondsAtLeast += coarse.seconds;
        e.stageTwoLeast.push_back(coarse.seconds);
        e.stageTwoMost.push_back(coarse.seconds);
        count(coarse);
    }
    std::ostringstream t;
    t << std::setprecision(3) << e.runs << " runs, " << e.steps << " steps in all, up to "
      << e.nodesPerBlockFinest << " nodes per block x " << blocks << " blocks; about ";
    if (e.secondsAtLeast < 0.99 * e.seconds)
        t << e.secondsAtLeast / 60.0 << " to " << e.seconds / 60.0
          << " min on 2 cores (stage 2 runs at the converged SDP: from the coarsest to the finest), ";
    else
        t << e.seconds / 60.0 << " min on 2 cores, ";
    t << "peak memory about " << e.memoryBytes / 1048576.0 << " MiB";
    if (ranks > 1) {
        t << "; on " << ranks << " MPI ranks x " << coresPerRank
          << (coresPerRank == 1.0 ? " core" : " cores") << ", largest runs first: about "
          << minutes(slabSecondsOnRanks(e, ranks, coresPerRank, false),
                     slabSecondsOnRanks(e, ranks, coresPerRank, true))
          << ", peak memory per rank the same";
    } else {
        // What MPI could do: one rank of 2 cores per run of the larger stage.
        const int enough = int(std::max(e.stageOne.size(), e.stageTwoMost.size()));
        if (enough > 1)
            t << "; under mpirun, " << enough << " ranks of 2 cores (one per run): about "
              << minutes(slabSecondsOnRanks(e, enough, 2.0, false),
                         slabSecondsOnRanks(e, enough, 2.0, true));
    }
    e.text = t.str();
    return e;
}

} // namespace lsdem
