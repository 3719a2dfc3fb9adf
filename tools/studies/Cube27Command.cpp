#include "studies/Cube27Command.h"

#include "studies/SphereSeriesCommand.h"
#include "studies/StudyCommandOptions.h"
#include "studies/ThreadLimit.h"

#include "common/CommandLine.h"
#include "common/PlotScripts.h"
#include "common/StudyOutput.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem {

namespace {

/// What the study writes into --out: its CSV and cube27.py's plots (one family per
/// formulation, so a rerun with other formulations leaves no stale ones).
const cli::StudyFiles kOwnFiles = {"cube27.csv", "cube27_*_by_nodes.png",
                                   "cube27_*_by_stiffness.png", "cube27_convergence.png"};

} // namespace

Cube27Command::Cube27Command(CLI::App& study)
    : mCommand(study.add_subcommand(
          "cube27",
          "27 spheres in a box pressed by its top wall (Fig. 4)\n\n"
          "27 equal spheres in a 3x3x3 simple-cubic stack filling the box [0, 6R]^3 (Feldfogel\n"
          "et al. 2024, Fig. 4): fixed floor and side walls, a top wall moving down at constant\n"
          "speed by --delta-max. The top wall's reaction P against its travel, for each\n"
          "formulation, node count and stiffness; against the continuum closed form\n"
          "9 pi k R delta^2 / (2 + 2 sqrt 2)^2."))
{
    Cube27Options& o = mOptions;
    // First: CLI11 applies options in the order they are added, so --full sets the defaults
    // that the other options then refine, wherever it stands on the command line.
    mCommand->add_flag_callback("--full", [&o] { o = cube27FullOptions(); },
                                "the paper-like study: nodes 500 ... 16000, 3 orientations,\n"
                                "voxel 0.05 (other options refine it)");
    addSphereSeriesOptions(*mCommand, o);

    const std::string loading = "Loading (mm, N, s, tonne)";
    cli::addNumber(*mCommand, "--delta-max", o.deltaMax, "top wall travel, mm")
        ->type_name("D")
        ->group(loading);
    mCommand
        ->add_option_function<std::string>(
            "--speed",
            [&o](const std::string& text) {
                o.speed = cli::parseNumber(text, "--speed");
                if (!(o.speed > 0))
                    throw Error("", "--speed must be positive, got " + numberText(o.speed));
            },
            "top wall speed, mm/s, for every run (default: each run's loading\n"
            "lasts --periods periods of a column's slowest mode, so v grows\n"
            "with sqrt(k))")
        ->type_name("V")
        ->group(loading);
    cli::addNumber(*mCommand, "--periods", o.periods,
                   "loading time in periods of a column's slowest mode")
        ->type_name("Q")
        ->group(loading);
    mCommand
        ->add_option_function<std::string>(
            "--steps",
            [&o](const std::string& text) {
                o.steps = cli::parseInteger(text, "--steps");
                if (o.steps <= 0) throw Error("", "--steps must be positive");
            },
            "loading steps (default: from --safety)")
        ->type_name("S")
        ->group(loading);
    cli::addNumber(*mCommand, "--safety", o.safety,
                   "time step as a fraction of the stiffest grain's limit")
        ->type_name("S")
        ->group(loading);
    cli::addInteger(*mCommand, "--points", o.points, "delta values recorded per run")
        ->type_name("P")
        ->group(loading);
    cli::addNumber(*mCommand, "--friction", o.friction,
                   "Coulomb coefficient (shear stiffness ks = 0.5 kn); original\n"
                   "and adapted only: single-node and volume have no shear springs")
        ->type_name("MU")
        ->group(loading);
    cli::addNumber(*mCommand, "--restitution", o.restitution,
                   "contact damping as a restitution coefficient")
        ->type_name("E")
        ->group(loading);
    cli::addNumber(*mCommand, "--damping", o.globalDamping, "global damping")
        ->type_name("L")
        ->group(loading);
    addOutputOptions(*mCommand, o.outDir, o.plots, o.quiet, "print only the summary");
    mCommand->footer("Prints the plan (each run's cost: 27 grains x nodes x steps) before "
                     "starting. Units: mm, N,\ns, tonne. Writes DIR/cube27.csv and, with "
                     "python3-matplotlib, DIR/cube27_*.png.");
}

bool Cube27Command::chosen() const
{
    return mCommand->parsed();
}

int Cube27Command::run(RunDistributor& ranks) const
{
    const Cube27Options& o = mOptions;
    checkCube27Options(o);
    // Refuses a --steps too few for any run, a --kn too stiff to plan and a plan too long,
    // before any run.
    planCube27(o);
    const ThreadLimit threads(0, ranks);
    if (!ranks.isRoot()) {
        runCube27(o, ranks);  // the runs rank 0 hands out; rank 0 writes everything
        return 0;
    }
    cli::checkOutputFolder(o.outDir);  // made once the runs are done, which may refuse input
    if (ranks.ranks() > 1) std::printf("%s\n", describeRanks(ranks, threads).c_str());

    const Stopwatch wall;
    const Cube27Result result = runCube27(o, ranks);
    cli::prepareOutputFolder(o.outDir, kOwnFiles, o.quiet);
    const std::string csv = o.outDir + "/cube27.csv";
    writeCube27Csv(result, o, csv);
    const double seconds = wall.seconds();

    std::printf("cube27: R = %g mm, voxel = %g mm, δ_max = %g mm, %d orientation(s), %s testing\n",
                o.radius, o.voxel, o.deltaMax, o.orientations, nodeTestingName(o.testing).c_str());
    std::printf("%-12s %8s %10s %14s %12s %14s %12s\n", "formulation", "N", "k", "P(δmax) [N]",
                "spread [N]", "P_exact [N]", "P/P_exact-1");
    double deltaEnd = 0.0;
    for (const Cube27Row& r : result.rows) deltaEnd = std::max(deltaEnd, r.delta);
    for (const Cube27Row& r : result.rows) {
        if (r.delta < deltaEnd * (1 - 1e-9)) continue;
        std::printf("%-12s %8.0f %10.3g %14.6g %12.3g %14.6g %+11.2f%%\n",
                    formulationName(r.formulation).c_str(), r.nodesActual, r.stiffness,
                    r.forceMean, r.forceMax - r.forceMin, r.forceExact,
                    100.0 * (r.forceMean / r.forceExact - 1.0));
    }
    std::printf("(original: P_exact uses kn* = kn·N/(4πR²), the continuum value of N uniformly "
                "spread nodes)\n");
    std::printf("time %.1f s (bake %.1f s, simulation %.1f s in %zu runs)\n", seconds,
                result.bakeSeconds, result.simulateSeconds, result.runs.size());
    std::printf("wrote %s\n", csv.c_str());
    return o.plots ? cli::drawPlots("cube27.py", {csv, o.outDir}) : 0;
}

} // namespace lsdem
