#include "studies/TwoSpheresCommand.h"

#include "studies/SphereSeriesCommand.h"
#include "studies/StudyCommandOptions.h"
#include "studies/ThreadLimit.h"

#include "common/CommandLine.h"
#include "common/PlotScripts.h"
#include "common/StudyOutput.h"

#include "lsdem/core/Stopwatch.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem {

namespace {

/// What the study writes into --out: its CSV and two_spheres.py's plots (one family per
/// formulation, so a rerun with other formulations leaves no stale ones).
const cli::StudyFiles kOwnFiles = {"two_spheres.csv", "two_spheres_*_by_nodes.png",
                                   "two_spheres_*_by_stiffness.png",
                                   "two_spheres_convergence.png"};

} // namespace

TwoSpheresCommand::TwoSpheresCommand(CLI::App& study)
    : mCommand(study.add_subcommand(
          "two-spheres",
          "Two spheres pressed together: P against the overlap (Fig. 1, 3)\n\n"
          "Two equal spheres pressed together along their centre line (Feldfogel et al. 2024,\n"
          "Fig. 1, 3): grain 0 fixed, grain 1 displaced by δ from 0 to --delta-max; the force P\n"
          "on the centre line, mean of random orientations, for each formulation, node count and\n"
          "stiffness."))
{
    TwoSpheresOptions& o = mOptions;
    addSphereSeriesOptions(*mCommand, o);
    const std::string loading = "Loading";
    cli::addNumber(*mCommand, "--delta-max", o.deltaMax, "largest overlap, mm")
        ->type_name("D")
        ->group(loading);
    cli::addInteger(*mCommand, "--steps", o.steps, "overlap steps")
        ->type_name("S")
        ->group(loading);
    addOutputOptions(*mCommand, o.outDir, o.plots, o.quiet, "print only the summary");
    mCommand->footer("Units: mm, N (forces), N/mm or N/mm^3 (stiffnesses). Writes "
                     "DIR/two_spheres.csv and, with\npython3-matplotlib, DIR/*.png.");
}

bool TwoSpheresCommand::chosen() const
{
    return mCommand->parsed();
}

int TwoSpheresCommand::run(RunDistributor& ranks) const
{
    const TwoSpheresOptions& o = mOptions;
    checkTwoSpheresOptions(o);
    const ThreadLimit threads(0, ranks);
    if (!ranks.isRoot()) {
        runTwoSpheres(o, ranks);  // the runs rank 0 hands out; rank 0 writes everything
        return 0;
    }
    cli::checkOutputFolder(o.outDir);  // made once the runs are done: a bake may refuse --voxel
    if (ranks.ranks() > 1) std::printf("%s\n", describeRanks(ranks, threads).c_str());

    if (!o.quiet) std::printf("%s\n", twoSpheresPlanText(o, ranks.ranks()).c_str());
    std::fflush(stdout);
    const Stopwatch wall;
    const TwoSpheresResult result = runTwoSpheres(o, ranks);
    cli::prepareOutputFolder(o.outDir, kOwnFiles, o.quiet);
    const std::string csv = o.outDir + "/two_spheres.csv";
    writeTwoSpheresCsv(result, o, csv);
    const double seconds = wall.seconds();

    // Summary: P at δ_max per formulation and N at the base stiffness, against the exact value.
    std::printf("two-spheres: R = %g mm, voxel = %g mm, δ_max = %g mm, %d orientations, %s testing\n",
                o.radius, o.voxel, o.deltaMax, o.orientations, nodeTestingName(o.testing).c_str());
    std::printf("%-12s %8s %10s %14s %12s %14s\n", "formulation", "N", "k", "P(δmax) [N]",
                "spread [N]", "vs its exact");
    for (const TwoSpheresRow& r : result.rows) {
        if (std::abs(r.delta - o.deltaMax) > 1e-12 * o.deltaMax) continue;
        const bool base = !o.stiffness.empty() || r.stiffness == defaultStiffness(r.formulation);
        if (!base) continue;
        std::printf("%-12s %8.0f %10.3g %14.6g %12.3g", formulationName(r.formulation).c_str(),
                    r.nodesActual, r.stiffness, r.forceMean, r.forceMax - r.forceMin);
        // The continuum laws against their own limits (P_exact); the others diverge.
        if (normalModel(r.formulation).convergesWithNodes())
            std::printf(" %+13.3f %%", 100.0 * (r.forceMean / r.forceExact - 1.0));
        std::printf("\n");
    }
    const NodeCheckStats& s = result.stats;
    const double contact = std::max(result.contactSeconds, 1e-9);
    std::printf("time %.2f s (bake %.2f s, contact %.3f s)\n", seconds, result.bakeSeconds,
                result.contactSeconds);
    std::printf("node checks: %lld considered (%.3g /s), %lld culled by bounds, %lld sampled "
                "(%.3g /s), %lld in contact\n",
                s.nodesConsidered, s.nodesConsidered / contact, s.nodesCulled, s.nodesSampled,
                s.nodesSampled / contact, s.nodesInContact);
    std::printf("wrote %s\n", csv.c_str());
    return o.plots ? cli::drawPlots("two_spheres.py", {csv, o.outDir}) : 0;
}

} // namespace lsdem
