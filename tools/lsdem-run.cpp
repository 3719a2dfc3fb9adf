/// lsdem-run: run a scene file (TOML) and write histories, ParaView frames and checkpoints;
/// under mpirun, one simulation split by space over the ranks (run/RunRanks.h).

#include "common/CommandLine.h"
#include "run/RunRanks.h"

#include "lsdem/run/SimulationRun.h"
#include "lsdem/core/Error.h"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace {

void onSignal(int)
{
    lsdem::requestStop();
    // A second signal takes the default action (stop at once).
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

/// What the command line gives.
struct RunCommandLine
{
    lsdem::RunOptions options;
    std::vector<std::string> scenes;
    long long threads = 0;
    bool quiet = false;
};

/// The options after the scene, in the order --help lists them.
void addOptions(CLI::App& app, RunCommandLine& c)
{
    using lsdem::Error;
    lsdem::RunOptions& options = c.options;
    app.add_option("scene", c.scenes, "the scene file (TOML)")->type_name("SCENE.toml");
    app.add_option("--out", options.outDir,
                   "output folder (created if missing; on restart: the checkpoint's\nfolder)")
        ->type_name("DIR");
    app.add_flag("--overwrite", options.overwrite,
                 "remove an earlier run's outputs (files lsdem wrote) from DIR first\n"
                 "(refused without it; other files there are kept)");
    app.add_option("--restart", options.restartPath,
                   "continue a run from its checkpoint, bit-identically")
        ->type_name("FILE");
    lsdem::cli::addThreads(app, c.threads,
                           "worker threads (default: all cores; under mpirun, the cores shared "
                           "among\nthe ranks on each machine); results do not depend on N");
    // A step count >= 1 into @a value.
    auto addStepCount = [&app](const std::string& name, long long& value, const std::string& what,
                               const std::string& help) {
        return app
            .add_option_function<std::string>(
                name,
                [&value, name, what](const std::string& text) {
                    value = lsdem::cli::parseInteger(text, name);
                    if (value < 1) throw Error("", name + " wants " + what + " >= 1");
                },
                help)
            ->type_name("N");
    };
    addStepCount("--stop-at-step", options.stopAtStep, "a step",
                 "stop at step N as if interrupted (checkpoint written)");
    CLI::Option* endTime =
        app.add_option_function<std::string>(
               "--end-time",
               [&options](const std::string& text) {
                   options.endTime = lsdem::cli::parseNumber(text, "--end-time");
                   if (!(options.endTime > 0.0))
                       throw Error("", "--end-time wants a time > 0, got " + text);
               },
               "end at this time instead of the scene's end (a restart: continue a\n"
               "finished run to it); the checkpoints keep it")
            ->type_name("T");
    addStepCount("--end-steps", options.endSteps, "a step count", "end after N steps in all, likewise")
        ->excludes(endTime);
    app.add_flag("-q,--quiet", c.quiet, "no progress line");
}

/// The run the parsed command line @a c asks for, on @a ranks (none: one process); its exit code.
int runCommandLine(RunCommandLine& c, lsdem::RunRanks* ranks)
{
    using lsdem::Error;
    lsdem::RunOptions& options = c.options;
    if (c.scenes.size() > 1)
        throw Error("", "more than one scene file given ('" + c.scenes[1] + "')",
                    "run one scene at a time");
    if (!c.scenes.empty()) options.scenePath = c.scenes[0];
    if (options.scenePath.empty() == options.restartPath.empty())
        throw Error("", "give either a scene file or --restart CHECKPOINT", "see lsdem-run --help");
    if (!options.scenePath.empty() && options.outDir.empty())
        throw Error("", "no output folder given", "pass --out DIR");
    options.progress = !c.quiet && isatty(STDERR_FILENO) && (!ranks || ranks->group().isRoot());
    long long threads = c.threads;
    if (ranks) {
        options.ranks = &ranks->group();
        // Ranks on one machine share its cores rather than each taking them all, and a rank
        // the launcher bound to fewer cores (TBB sees its affinity) keeps to those.
        if (threads == 0) {
            const int machine = static_cast<int>(std::thread::hardware_concurrency());
            const int share = machine / std::max(1, ranks->ranksOnThisMachine());
            threads = std::max(1, std::min(tbb::info::default_concurrency(), share));
        }
    }
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    options.threads = static_cast<int>(
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const lsdem::RunResult result = lsdem::runSimulation(options, std::cout);
    return result.interrupted ? 130 : 0;
}

} // namespace

int main(int argc, char** argv)
{
    // Under mpirun: MPI starts here, and only rank 0 prints (its errors are every rank's).
    std::unique_ptr<lsdem::RunRanks> ranks;
    if (const int failed = lsdem::cli::runTool("lsdem-run", [&] {
            ranks = lsdem::startRunRanks(argc, argv);
            return 0;
        }))
        return failed;
    if (ranks && !ranks->group().isRoot() && !std::freopen("/dev/null", "w", stdout))
        return 3;

    CLI::App app(
        "Run the simulation described by a scene file (see docs/scenes.md) and write to DIR:\n"
        "energy.csv, boundary_<name>.csv (displacement and reaction of each boundary), "
        "grains.csv,\nframes.pvd + frames_*.vtu (ParaView, if [output] vtk_period is set; under "
        "mpirun a\n.pvtu per frame and a .vtu piece per rank) and checkpoint.lsdem.\n\n"
        "  lsdem-run SCENE.toml --out DIR [options]\n"
        "  lsdem-run --restart DIR/checkpoint.lsdem [options]\n"
        "  mpirun -n N lsdem-run SCENE.toml --out DIR   (split by space: each rank "
        "owns a sub-domain's grains; the same bytes)",
        "lsdem-run");
    lsdem::cli::applyConventions(app);
    app.footer("Ctrl-C (SIGINT) or SIGTERM stops after the current step and writes a checkpoint; "
               "a second\nCtrl-C stops at once. Exit codes: 0 finished, 1 bad input, 3 internal "
               "error, 130 stopped.");
    RunCommandLine c;
    addOptions(app, c);
    const auto body = [&] {
        if (const auto exitCode = lsdem::cli::parse(app, argc, argv)) return *exitCode;
        return runCommandLine(c, ranks.get());
    };
    return ranks ? ranks->run("lsdem-run", body) : lsdem::cli::runTool("lsdem-run", body);
}
