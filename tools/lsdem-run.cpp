/// lsdem-run: run a scene file (TOML) and write histories, ParaView frames and checkpoints.

#include "common/CommandLine.h"

#include "lsdem/run/SimulationRun.h"
#include "lsdem/ls/Error.h"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace {

void onSignal(int)
{
    lsdem::requestStop();
    // A second signal takes the default action (stop at once).
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

} // namespace

int main(int argc, char** argv)
{
    using lsdem::Error;
    CLI::App app(
        "Run the simulation described by a scene file (see docs/scenes.md) and write to DIR:\n"
        "energy.csv, boundary_<name>.csv (displacement and reaction of each boundary), "
        "grains.csv,\nframes.pvd + frames_*.vtu (ParaView, if [output] vtk_period is set) and "
        "checkpoint.lsdem.\n\n"
        "  lsdem-run SCENE.toml --out DIR [options]\n"
        "  lsdem-run --restart DIR/checkpoint.lsdem [options]",
        "lsdem-run");
    lsdem::cli::applyConventions(app);
    app.footer("Ctrl-C (SIGINT) or SIGTERM stops after the current step and writes a checkpoint; "
               "a second\nCtrl-C stops at once. Exit codes: 0 finished, 1 bad input, 3 internal "
               "error, 130 stopped.");
    lsdem::RunOptions options;
    std::vector<std::string> scenes;
    long long threads = 0;
    bool quiet = false;
    app.add_option("scene", scenes, "the scene file (TOML)")->type_name("SCENE.toml");
    app.add_option("--out", options.outDir,
                   "output folder (created if missing; on restart: the checkpoint's\nfolder)")
        ->type_name("DIR");
    app.add_option("--restart", options.restartPath,
                   "continue a run from its checkpoint, bit-identically")
        ->type_name("FILE");
    app.add_option_function<std::string>(
           "--threads",
           [&threads](const std::string& text) {
               threads = lsdem::cli::parseInteger(text, "--threads");
               if (threads < 1) throw Error("", "--threads wants a number >= 1");
           },
           "worker threads (default: all cores); results do not depend on N")
        ->type_name("N");
    app.add_option_function<std::string>(
           "--stop-at-step",
           [&options](const std::string& text) {
               options.stopAtStep = lsdem::cli::parseInteger(text, "--stop-at-step");
               if (options.stopAtStep < 1) throw Error("", "--stop-at-step wants a step >= 1");
           },
           "stop at step N as if interrupted (checkpoint written)")
        ->type_name("N");
    app.add_flag("-q,--quiet", quiet, "no progress line");

    return lsdem::cli::runTool("lsdem-run", [&] {
        if (const auto exitCode = lsdem::cli::parse(app, argc, argv)) return *exitCode;
        if (scenes.size() > 1)
            throw Error("", "more than one scene file given ('" + scenes[1] + "')",
                        "run one scene at a time");
        if (!scenes.empty()) options.scenePath = scenes[0];
        if (options.scenePath.empty() == options.restartPath.empty())
            throw Error("", "give either a scene file or --restart CHECKPOINT",
                        "see lsdem-run --help");
        if (!options.scenePath.empty() && options.outDir.empty())
            throw Error("", "no output folder given", "pass --out DIR");
        options.progress = !quiet && isatty(STDERR_FILENO);

        std::unique_ptr<tbb::global_control> limit;
        if (threads > 0)
            limit = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
        std::signal(SIGINT, onSignal);
        std::signal(SIGTERM, onSignal);
        const lsdem::RunResult result = lsdem::runSimulation(options, std::cout);
        return result.interrupted ? 130 : 0;
    });
}
