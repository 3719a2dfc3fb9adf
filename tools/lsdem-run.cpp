/// lsdem-run: run a scene file (TOML) and write histories, ParaView frames and checkpoints.

#include "common/CommandLine.h"

#include "lsdem/run/SimulationRun.h"
#include "lsdem/ls/Error.h"

#include <tbb/global_control.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

namespace {

const char* const kUsage = R"(usage: lsdem-run SCENE.toml --out DIR [options]
       lsdem-run --restart DIR/checkpoint.lsdem [options]

Run the simulation described by a scene file (see docs/scenes.md) and write to DIR:
energy.csv, boundary_<name>.csv (displacement and reaction of each boundary), grains.csv,
frames.pvd + frames_*.vtu (ParaView, if [output] vtk_period is set) and checkpoint.lsdem.

  --out DIR            output folder (created if missing; on restart: the checkpoint's folder)
  --restart FILE       continue a run from its checkpoint, bit-identically
  --threads N          worker threads (default: all cores); results do not depend on N
  --stop-at-step N     stop at step N as if interrupted (checkpoint written)
  -q, --quiet          no progress line
  -h, --help           this text

Ctrl-C (SIGINT) or SIGTERM stops after the current step and writes a checkpoint; a second
Ctrl-C stops at once. Exit codes: 0 finished, 1 bad input, 3 internal error, 130 stopped.
)";

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
    return lsdem::cli::runTool("lsdem-run", [&] {
        lsdem::cli::Arguments args(argc, argv);
        lsdem::RunOptions options;
        long long threads = 0;
        bool quiet = false;
        while (!args.done()) {
            const std::string a = args.next();
            if (a == "-h" || a == "--help") {
                std::fputs(kUsage, stdout);
                return 0;
            } else if (a == "--out") {
                options.outDir = args.value(a);
            } else if (a == "--restart") {
                options.restartPath = args.value(a);
            } else if (a == "--threads") {
                threads = args.integer(a);
                if (threads < 1) throw lsdem::Error("", "--threads wants a number >= 1");
            } else if (a == "--stop-at-step") {
                options.stopAtStep = args.integer(a);
                if (options.stopAtStep < 1) throw lsdem::Error("", "--stop-at-step wants a step >= 1");
            } else if (a == "-q" || a == "--quiet") {
                quiet = true;
            } else if (!a.empty() && a[0] == '-') {
                throw lsdem::Error("", "unknown option " + a, "see lsdem-run --help");
            } else if (options.scenePath.empty()) {
                options.scenePath = a;
            } else {
                throw lsdem::Error("", "more than one scene file given ('" + a + "')",
                                   "run one scene at a time");
            }
        }
        if (options.scenePath.empty() == options.restartPath.empty())
            throw lsdem::Error("", "give either a scene file or --restart CHECKPOINT",
                               "see lsdem-run --help");
        if (!options.scenePath.empty() && options.outDir.empty())
            throw lsdem::Error("", "no output folder given", "pass --out DIR");
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
