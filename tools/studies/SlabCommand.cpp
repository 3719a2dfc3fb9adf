#include "studies/SlabCommand.h"

#include "studies/SlabPanel.h"
#include "studies/StudyCommandOptions.h"
#include "studies/ThreadLimit.h"

#include "common/CommandLine.h"
#include "common/PlotScripts.h"
#include "common/StudyOutput.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <thread>

namespace lsdem {

namespace {

/// What the study writes into --out: its CSVs and summary, the scene with its block mesh,
/// the baked blocks (one per discretization) and slab.py's plots. Removed before the runs, as
/// the files are written from the first run on; this run writes again what it needs.
const cli::StudyFiles kOwnFiles = {
    "slab.csv",         "slab_runs.csv",        "slab_snapshots.csv",
    "slab_failure.txt", "slab_scene.toml",      "slab_block.obj",
    "slab_sdp.png",     "slab_vdp.png",         "slab_convergence.png",
    "slab_blocks.png",  "slab_snapshots_*.png", "assets/block_sdp*_vdp*.vdb"};

} // namespace

// Long by nature: one entry per option, in the order --help lists them.
SlabCommand::SlabCommand(CLI::App& study)
    : mCommand(study.add_subcommand(
          "slab",
          "An interlocked slab pushed by an indenter (Fig. 5, 6)\n\n"
          "The interlocked slab (Feldfogel et al. 2024, Fig. 5, 6): n x n planar blocks with\n"
          "faces inclined alternately by +-angle, held by a rigid frame (a ring of fixed blocks\n"
          "of the same shape), the central block pushed down by a sphere at constant speed. P\n"
          "against the indenter's displacement delta per formulation and discretization; the\n"
          "two-way study refines SDP at fixed VDP (every formulation), then VDP at the\n"
          "converged SDP (adapted), and reports VDP/SDP."))
{
    using cli::addInteger;
    using cli::addNumber;
    using cli::addNumbers;
    SlabStudyOptions& o = mOptions;
    // First: CLI11 applies options in the order they are added, so --full sets the lists that
    // the other options then override, wherever it stands on the command line.
    CLI::Option* full =
        mCommand->add_flag_callback("--full", [&o] { o = slabFullOptions(); },
                                    "the full study: SDP 1 0.7 0.5 0.35 0.25 0.18 0.125 (original "
                                    "to\n0.25) at VDP 0.035, then VDP 0.4 0.28 0.2 ... 0.035 (steps "
                                    "of\nsqrt 2); other options refine it");
    mCommand
        ->add_flag_callback("--seed", [&o] { o = slabSeedOptions(); },
                            "the seed's resolution, adapted only: SDP 1 0.7 ... 0.09 0.06 at\n"
                            "VDP 0.025, then VDP 0.4 0.28 ... 0.035 0.025 (steps of sqrt 2);\n"
                            "about 20 min on 2 cores (see --estimate); mpirun spreads its runs")
        ->excludes(full);

    const std::string panel = "Panel";
    addInteger(*mCommand, "--blocks", o.panel.blocksPerSide, "blocks per side, odd")
        ->type_name("N")
        ->group(panel);
    addNumber(*mCommand, "--block-size", o.panel.blockSize, "grid pitch, mm")
        ->type_name("L")
        ->group(panel);
    addNumber(*mCommand, "--thickness", o.panel.thickness, "mm")->type_name("T")->group(panel);
    addNumber(*mCommand, "--angle", o.panel.angleDeg, "interlocking angle, degrees")
        ->type_name("A")
        ->group(panel);

    const std::string discretizations = "Discretizations (mm)";
    CLI::Option* sdps = addNumbers(*mCommand, "--sdp", o.sdps, "node spacings of stage 1")
                            ->type_name("S")
                            ->group(discretizations);
    CLI::Option* originalSdps =
        addNumbers(*mCommand, "--sdp-original", o.originalSdps,
                   "the subset run with original (and single-node), whose time step\n"
                   "shrinks with the node count (with --sdp alone: all of them)")
            ->type_name("S")
            ->group(discretizations);
    // --sdp alone: one list for every formulation.
    mCommand->callback([sdps, originalSdps, &o] {
        if (sdps->count() > 0 && originalSdps->count() == 0) o.originalSdps.clear();
    });
    addNumber(*mCommand, "--vdp-fixed", o.fixedVdp, "voxel of stage 1")
        ->type_name("V")
        ->group(discretizations);
    addNumbers(*mCommand, "--vdp", o.vdps, "voxels of stage 2")
        ->type_name("V")
        ->group(discretizations);
    mCommand->add_flag_callback("--no-two-way", [&o] { o.twoWay = false; }, "stage 1 only")
        ->group(discretizations);
    addNumber(*mCommand, "--tolerance", o.tolerance,
              "converged: the loading branch (RMS) and the peak within X of the\n"
              "finest run's peak P, and the same failure mode")
        ->type_name("X")
        ->group(discretizations);

    const std::string loading = "Loading and material (mm, N, s, tonne)";
    addFormulationOption(*mCommand, o.formulations)->group(loading);
    addNumber(*mCommand, "--delta-max", o.deltaMax,
              "indenter travel (default: twice the thickness)")
        ->type_name("D")
        ->default_str("")
        ->group(loading);
    addNumber(*mCommand, "--speed", o.speed,
              "indenter speed, mm/s (quasi-static: within 1% of 200)")
        ->type_name("V")
        ->group(loading);
    addNumber(*mCommand, "--indenter-radius", o.indenterRadius, "mm")
        ->type_name("R")
        ->group(loading);
    addNumber(*mCommand, "--young", o.material.youngModulus, "MPa (glass); kn* = E/L")
        ->type_name("E")
        ->group(loading);
    addNumber(*mCommand, "--poisson", o.material.poisson, "ks* = kn*/(2(1+nu))")
        ->type_name("NU")
        ->group(loading);
    addNumber(*mCommand, "--density", o.material.density, "t/mm^3")
        ->type_name("RHO")
        ->group(loading);
    addNumber(*mCommand, "--friction", o.material.friction, "Coulomb coefficient")
        ->type_name("MU")
        ->group(loading);
    addNumber(*mCommand, "--restitution", o.material.restitution, "contact damping")
        ->type_name("E")
        ->group(loading);
    addNumber(*mCommand, "--damping", o.material.globalDamping, "global damping")
        ->type_name("L")
        ->group(loading);
    addNumber(*mCommand, "--gravity", o.material.gravity, "mm/s^2")
        ->type_name("G")
        ->group(loading);
    addNumber(*mCommand, "--kn-star", o.knStar, "override kn*, N/mm^3")
        ->type_name("K")
        ->default_str("")
        ->group(loading);
    addNumber(*mCommand, "--ks-star", o.ksStar, "override ks*, N/mm^3")
        ->type_name("K")
        ->default_str("")
        ->group(loading);
    addNumber(*mCommand, "--kn", o.knOriginal,
              "original kn, N/mm (default kn*(sqrt3/2)s_ref^2, s_ref = the\n"
              "coarsest SDP)")
        ->type_name("K")
        ->default_str("")
        ->group(loading);
    addNumber(*mCommand, "--reference-sdp", o.referenceSdp, "s_ref for the default kn")
        ->type_name("S")
        ->default_str("")
        ->group(loading);
    addTestingOption(*mCommand, o.testing)->group(loading);
    addNumber(*mCommand, "--safety", o.timeStepSafety,
              "time step fraction of the stability limit, at most 0.5")
        ->type_name("S")
        ->group(loading);

    const std::string output = "Output";
    addNumbers(*mCommand, "--snapshots", o.snapshotDeltas,
               "delta of the failure snapshots (default 6 from 0 to delta-max)")
        ->type_name("D")
        ->group(output);
    addInteger(*mCommand, "--samples", o.samples, "P-delta rows per run")
        ->type_name("N")
        ->group(output);
    cli::addThreads(*mCommand, mThreads, "worker threads (default: all cores)")->group(output);
    addOutputOptions(*mCommand, o.outDir, o.plots, o.quiet, "print only the summary");
    mCommand->add_flag_callback("--no-scene", [&o] { o.writeScene = false; },
                                "do not write slab_scene.toml / slab_block.obj")
        ->group(output);
    mCommand->add_flag("--estimate", mEstimateOnly, "print the cost and stop")->group(output);
    mCommand->footer(
        "Writes DIR/slab.csv (P-delta), slab_runs.csv (one row per run), slab_snapshots.csv,\n"
        "slab_failure.txt, slab_scene.toml + assets/ (the converged case, for lsdem-run) and, "
        "with\npython3-matplotlib, DIR/slab_*.png.");
}

bool SlabCommand::chosen() const
{
    return mCommand->parsed();
}

int SlabCommand::run(RunDistributor& ranks) const
{
    const SlabStudyOptions& o = mOptions;
    checkSlabStudyOptions(o);
    const SlabPanel panel(o.panel);
    const ThreadLimit threads(mThreads, ranks);
    if (!ranks.isRoot()) {
        // The runs rank 0 hands out (their lines go to rank 0 with their results); rank 0
        // prints and writes everything.
        if (!mEstimateOnly) runSlabStudy(o, o.quiet ? nullptr : &std::cout, {}, ranks);
        return 0;
    }
    const SlabStiffness k = slabStiffness(o);
    const double coresPerRank = threads.threads() > 0
                                    ? double(threads.threads())
                                    : double(std::max(1u, std::thread::hardware_concurrency()));
    const SlabCostEstimate cost = estimateSlabCost(o, ranks.ranks(), coresPerRank);
    std::printf("slab: %dx%d blocks, L = %g mm, t = %g mm, angle %g deg; indenter R = %g mm at "
                "%g mm/s to delta = %g mm\n"
                "      kn* = %g N/mm^3, ks* = %g N/mm^3 (adapted), kn = %g N/mm (original), mu = %g\n"
                "cost: %s\n",
                o.panel.blocksPerSide, o.panel.blocksPerSide, o.panel.blockSize, o.panel.thickness,
                o.panel.angleDeg, o.indenterRadius, o.speed, slabDeltaMax(o), k.knStar, k.ksStar,
                k.kn, o.material.friction, cost.text.c_str());
    std::fflush(stdout);
    if (mEstimateOnly) return 0;

    cli::prepareOutputFolder(o.outDir, kOwnFiles, o.quiet);
    if (ranks.ranks() > 1) std::printf("%s\n", describeRanks(ranks, threads).c_str());

    const SlabStudyResult result =
        runSlabStudy(o, o.quiet ? nullptr : &std::cout,
                     [&](const SlabStudyResult& sofar) { writeSlabOutputs(sofar, o, panel); },
                     ranks);
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
    return o.plots ? cli::drawPlots("slab.py", {o.outDir}) : 0;
}

} // namespace lsdem
