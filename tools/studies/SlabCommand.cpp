#include "studies/SlabCommand.h"

#include "studies/SlabPanel.h"
#include "studies/SlabStudy.h"

#include "common/StudyOutput.h"

#include "lsdem/ls/Error.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

namespace lsdem {

const char* slabUsage()
{
    return R"(usage: lsdem-study slab [options]

The interlocked slab (Feldfogel et al. 2024, Fig. 5, 6): n x n planar blocks with faces
inclined alternately by +-angle, held by a rigid frame (a ring of fixed blocks of the same
shape), the central block pushed down by a sphere at constant speed. P against the indenter's
displacement delta per formulation and discretization; the two-way study refines SDP at fixed
VDP (every formulation), then VDP at the converged SDP (adapted), and reports VDP/SDP.

panel:
  --blocks N           blocks per side, odd (default 5)
  --block-size L       grid pitch, mm (default 8)
  --thickness T        mm (default 3)
  --angle A            interlocking angle, degrees (default 15)
discretizations (mm):
  --sdp S...           node spacings of stage 1 (default 1 0.7 0.5 0.35 0.25)
  --sdp-original S...  the subset run with original (and single-node), whose time step
                       shrinks with the node count (default 1 0.7 0.5 0.35; with --sdp
                       alone: all of them)
  --vdp-fixed V        voxel of stage 1 (default 0.05)
  --vdp V...           voxels of stage 2 (default 0.4 0.2 0.14 0.1 0.05)
  --full               the full study: SDP 1 0.7 0.5 0.35 0.25 0.18 0.125 (original to
                       0.25) at VDP 0.035, then VDP 0.4 0.28 0.2 ... 0.035 (steps of
                       sqrt 2)
  --no-two-way         stage 1 only
  --tolerance X        converged: the loading branch (RMS) and the peak within X of the
                       finest run's peak P (default 0.05), and the same failure mode
loading and material (mm, N, s, tonne):
  --formulation F...   original, adapted, single-node, volume (default: adapted original)
  --delta-max D        indenter travel (default: twice the thickness)
  --speed V            indenter speed, mm/s (default 1000; quasi-static: within 1% of 200)
  --indenter-radius R  mm (default 2.5)
  --young E            MPa (default 7e4, glass); kn* = E/L
  --poisson NU         (default 0.22); ks* = kn*/(2(1+nu))
  --density RHO        t/mm^3 (default 2.5e-9)
  --friction MU        (default 0.4)
  --restitution E      contact damping (default 0.5)
  --damping L          global damping (default 0.3)
  --gravity G          mm/s^2 (default 9810)
  --kn-star K          override kn*, N/mm^3
  --ks-star K          override ks*, N/mm^3
  --kn K               original kn, N/mm (default kn*(sqrt3/2)s_ref^2, s_ref = coarsest SDP)
  --reference-sdp S    s_ref for the default kn
  --testing T          symmetric (default) or one-way
  --safety S           time step fraction of the stability limit, at most 0.5 (default 0.3)
outputs:
  --snapshots D...     delta of the failure snapshots (default 6 from 0 to delta-max)
  --samples N          P-delta rows per run (default 200)
  --threads N          worker threads (default: all cores)
  --out DIR            output folder (default results/slab)
  --no-plots           CSV and text only
  --no-scene           do not write slab_scene.toml / slab_block.obj
  --estimate           print the cost and stop
  -q, --quiet          print only the summary

Writes DIR/slab.csv (P-delta), slab_runs.csv (one row per run), slab_snapshots.csv,
slab_failure.txt, slab_scene.toml + assets/ (the converged case, for lsdem-run) and, with
python3-matplotlib, DIR/slab_*.png.
)";
}

int runSlabCommand(cli::Arguments& args, const std::string& plotDir)
{
    // --full first: it sets the lists that later options may override.
    SlabStudyOptions o;
    for (cli::Arguments scan = args; !scan.done();)
        if (scan.next() == "--full") o = slabFullOptions();
    long long threads = 0;
    bool estimateOnly = false;
    bool originalGiven = false;
    while (!args.done()) {
        const std::string a = args.next();
        if (a == "-h" || a == "--help") {
            std::cout << slabUsage();
            return 0;
        } else if (a == "--full") {
        } else if (a == "--blocks") {
            o.panel.blocksPerSide = int(std::clamp<long long>(args.integer(a), -1, 1000000));
        } else if (a == "--block-size") {
            o.panel.blockSize = args.number(a);
        } else if (a == "--thickness") {
            o.panel.thickness = args.number(a);
        } else if (a == "--angle") {
            o.panel.angleDeg = args.number(a);
        } else if (a == "--sdp") {
            o.sdps = args.numbers(a);
            if (!originalGiven) o.originalSdps.clear();  // the same list for every formulation
        } else if (a == "--sdp-original") {
            o.originalSdps = args.numbers(a);
            originalGiven = true;
        } else if (a == "--vdp-fixed") {
            o.fixedVdp = args.number(a);
        } else if (a == "--vdp") {
            o.vdps = args.numbers(a);
        } else if (a == "--no-two-way") {
            o.twoWay = false;
        } else if (a == "--tolerance") {
            o.tolerance = args.number(a);
        } else if (a == "--formulation") {
            o.formulations.clear();
            for (const std::string& v : args.values(a)) o.formulations.push_back(parseFormulation(v));
        } else if (a == "--delta-max") {
            o.deltaMax = args.number(a);
        } else if (a == "--speed") {
            o.speed = args.number(a);
        } else if (a == "--indenter-radius") {
            o.indenterRadius = args.number(a);
        } else if (a == "--young") {
            o.material.youngModulus = args.number(a);
        } else if (a == "--poisson") {
            o.material.poisson = args.number(a);
        } else if (a == "--density") {
            o.material.density = args.number(a);
        } else if (a == "--friction") {
            o.material.friction = args.number(a);
        } else if (a == "--restitution") {
            o.material.restitution = args.number(a);
        } else if (a == "--damping") {
            o.material.globalDamping = args.number(a);
        } else if (a == "--gravity") {
            o.material.gravity = args.number(a);
        } else if (a == "--ks-star") {
            o.ksStar = args.number(a);
        } else if (a == "--kn-star") {
            o.knStar = args.number(a);
        } else if (a == "--kn") {
            o.knOriginal = args.number(a);
        } else if (a == "--reference-sdp") {
            o.referenceSdp = args.number(a);
        } else if (a == "--testing") {
            o.testing = parseNodeTesting(args.value(a));
        } else if (a == "--safety") {
            o.timeStepSafety = args.number(a);
        } else if (a == "--snapshots") {
            o.snapshotDeltas = args.numbers(a);
        } else if (a == "--samples") {
            o.samples = int(std::clamp<long long>(args.integer(a), -1, 1000000000));
        } else if (a == "--threads") {
            threads = args.integer(a);
            if (threads < 1) throw Error("", "--threads wants a number >= 1");
        } else if (a == "--out") {
            o.outDir = args.value(a);
        } else if (a == "--no-plots") {
            o.plots = false;
        } else if (a == "--no-scene") {
            o.writeScene = false;
        } else if (a == "--estimate") {
            estimateOnly = true;
        } else if (a == "-q" || a == "--quiet") {
            o.quiet = true;
        } else {
            throw Error("", "unknown option '" + a + "'", "see lsdem-study slab --help");
        }
    }
    checkSlabStudyOptions(o);
    const SlabPanel panel(o.panel);
    const SlabStiffness k = slabStiffness(o);
    const SlabCostEstimate cost = estimateSlabCost(o);
    std::printf("slab: %dx%d blocks, L = %g mm, t = %g mm, angle %g deg; indenter R = %g mm at "
                "%g mm/s to delta = %g mm\n"
                "      kn* = %g N/mm^3, ks* = %g N/mm^3 (adapted), kn = %g N/mm (original), mu = %g\n"
                "cost: %s\n",
                o.panel.blocksPerSide, o.panel.blocksPerSide, o.panel.blockSize, o.panel.thickness,
                o.panel.angleDeg, o.indenterRadius, o.speed, slabDeltaMax(o), k.knStar, k.ksStar,
                k.kn, o.material.friction, cost.text.c_str());
    std::fflush(stdout);
    if (estimateOnly) return 0;

    cli::prepareOutputFolder(o.outDir);

    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));
    const SlabStudyResult result =
        runSlabStudy(o, o.quiet ? nullptr : &std::cout,
                     [&](const SlabStudyResult& sofar) { writeSlabOutputs(sofar, o, panel); });
    writeSlabOutputs(result, o, panel);

    std::printf("\n%-9s %-6s %6s %6s %7s %8s %10s %10s %9s\n", "stage", "formul.", "SDP", "VDP",
                "nodes", "steps", "P_max [N]", "drop [mm]", "time [s]");
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const SlabRunResult& r = result.runs[i];
        double peak = 0;
        for (const SlabSample& s : r.curve) peak = std::max(peak, s.force);
        std::printf("%-9s %-7s %6.3g %6.3g %7d %8lld %10.4g %10.3g %9.1f%s\n", result.stage[i].c_str(),
                    formulationName(r.formulation).c_str(), r.sdp, r.vdp, r.nodes, r.steps, peak,
                    r.curve.empty() ? 0.0 : r.curve.back().centralDrop, r.runSeconds,
                    r.stopped ? "  stopped" : "");
    }
    std::printf("converged SDP %g mm%s, VDP %g mm%s: VDP/SDP = %.3g (the paper: 0.025/0.06 = 0.42)\n",
                result.convergedSdp, result.sdpConverged ? "" : " (NOT converged: refine further)",
                result.convergedVdp,
                !o.twoWay ? " (fixed)" : result.vdpConverged ? "" : " (NOT converged: refine further)",
                result.convergedVdp / result.convergedSdp);
    if (result.convergedRun >= 0)
        std::printf("%s", slabFailureSummary(panel, result.runs[result.convergedRun]).c_str());
    std::printf("time %.1f s; wrote %s/slab.csv, slab_runs.csv, slab_snapshots.csv, slab_failure.txt\n",
                result.wallSeconds, o.outDir.c_str());
    return o.plots ? cli::drawPlots(plotDir + "/slab.py", {o.outDir}) : 0;
}

} // namespace lsdem
