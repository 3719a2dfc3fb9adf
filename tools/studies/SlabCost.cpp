#include "studies/SlabCost.h"

#include "studies/SlabModel.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace lsdem {

namespace {

/// Nodes on a block surface of area @a area remeshed at edge length @a sdp (equilateral
/// triangles, two per vertex).
double nodesForSpacing(double area, double sdp) { return 2.0 * area / (std::sqrt(3.0) * sdp * sdp); }

double blockSurfaceArea(const SlabPanel& panel) { return surfaceArea(panel.referenceMesh()); }

} // namespace

SlabCostEstimate estimateSlabCost(const SlabStudyOptions& o)
{
    SlabCostEstimate e;
    const SlabPanel panel(o.panel);
    const double area = blockSurfaceArea(panel);
    const double blocks = double(panel.n()) * panel.n();
    const SlabStiffness k = slabStiffness(o);
    const double mass = o.material.density * panel.blockVolume();
    // Measured on this machine (2 shared cores, see docs/slab.md): about 75 ns of wall time
    // per block node and step, both directions of symmetric testing and the shear history
    // included.
    const double secondsPerNodeStep = 75e-9;
    struct RunCost
    {
        double seconds = 0.0, nodes = 0.0, bytes = 0.0;
        long long steps = 0;
    };
    auto runCost = [&](Formulation f, double sdp, double vdp) {
        RunCost c;
        c.nodes = nodesForSpacing(area, sdp);
        const ContactModel model = slabContactModel(o, f);
        const double face = model.normal().patchStiffness(
            model.normalStiffness, panel.sharedFaceArea(), area / c.nodes);
        const double dt =
            o.timeStepSafety * 2.0 * std::sqrt(mass / (2.0 * face * std::max(1.0, k.ksStar / k.knStar)));
        // Clamped before the cast: absurd inputs are refused by the caller, not undefined here.
        c.steps = static_cast<long long>(std::min(std::ceil(slabDeltaMax(o) / (o.speed * dt)), 1e15));
        c.seconds = c.steps * blocks * c.nodes * secondsPerNodeStep;
        // The peak is the bake: measured 816 MB resident for the block at VDP 0.025 mm (a
        // 58 MiB asset), about 48 bytes per voxel of the block's padded bounding box. Then
        // the run: nodes (position, normal, area) and the shear history per node in contact
        // (a std::map entry, ~80 bytes) for about half the nodes of every block.
        const double box = (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                           (o.panel.blockSize + 2 * panel.overhang() + 10 * vdp) *
                           (o.panel.thickness + 10 * vdp);
        c.bytes = 48.0 * box / (vdp * vdp * vdp) + c.nodes * 56.0 + blocks * c.nodes * 0.5 * 80.0;
        return c;
    };
    // Counted runs: the upper bound's (stage 2 at the finest SDP).
    auto count = [&](const RunCost& c) {
        ++e.runs;
        e.steps += c.steps;
        e.seconds += c.seconds;
        e.nodesPerBlockFinest = std::max(e.nodesPerBlockFinest, c.nodes);
        e.memoryBytes = std::max(e.memoryBytes, c.bytes);
    };
    const std::vector<double> sdps = slabCoarseToFine(o.sdps);
    for (double s : sdps)
        for (Formulation f : o.formulations)
            if (slabStageOneRuns(o, f, s)) count(runCost(f, s, o.fixedVdp));
    e.secondsAtLeast = e.seconds;
    if (o.twoWay) {
        // Stage 2 runs at the converged SDP, not known yet: it costs least at the coarsest SDP
        // and most at the finest.
        const std::vector<double> vdps = slabCoarseToFine(o.vdps);
        for (double v : vdps) {
            if (std::abs(v - o.fixedVdp) <= 1e-12) continue;  // shared with stage 1
            e.secondsAtLeast += runCost(Formulation::Adapted, sdps.front(), v).seconds;
            count(runCost(Formulation::Adapted, sdps.back(), v));
        }
        const RunCost coarse = runCost(Formulation::Adapted, sdps.front(), vdps.front());  // snapshots
        e.secondsAtLeast += coarse.seconds;
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
    e.text = t.str();
    return e;
}

} // namespace lsdem
