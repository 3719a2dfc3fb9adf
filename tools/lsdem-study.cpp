/// lsdem-study: the paper's studies as one command each; writes CSV and PNG plots.

#include "common/CommandLine.h"
#include "studies/Cube27Command.h"
#include "studies/RunDistributor.h"
#include "studies/SlabCommand.h"
#include "studies/TriaxialCommand.h"
#include "studies/TwoSpheresCommand.h"
#include "studies/verify/VerifyCommand.h"

#include "lsdem/core/Error.h"

#include <CLI/CLI.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <functional>
#include <iostream>
#include <memory>
#include <utility>

namespace {

/// Send this process's stdout and stderr to /dev/null.
void silenceOutput()
{
    std::fflush(stdout);
    std::fflush(stderr);
    const int nowhere = ::open("/dev/null", O_WRONLY);
    if (nowhere < 0) return;
    ::dup2(nowhere, STDOUT_FILENO);
    ::dup2(nowhere, STDERR_FILENO);
    ::close(nowhere);
}

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    // Under mpirun the study's runs are spread over the ranks (RunDistributor.h); MPI lives
    // until the end of main.
    std::unique_ptr<RunDistributor> ranks;
    if (const int failed = cli::runTool("lsdem-study", [&] {
            ranks = makeRunDistributor(argc, argv, "lsdem-study");
            return 0;
        }))
        return failed;
    // The other ranks only do the runs rank 0 hands them: rank 0 prints (and writes) for all,
    // so a message appears once, and errors of a run reach it with the run's result.
    if (!ranks->isRoot()) silenceOutput();

    CLI::App app("The studies of Feldfogel et al. (2024), one command each: CSV files and, with "
                 "python3-matplotlib,\nPNG plots in the --out folder.",
                 "lsdem-study");
    cli::applyConventions(app);
    app.require_subcommand(1, 1);
    app.footer("`lsdem-study STUDY --help` lists a study's options. Exit codes: 0 done, 1 bad "
               "input,\n2 no arguments (this help on stderr), 3 internal error, 4 results "
               "written but plots missing.\n`mpirun -n N lsdem-study STUDY ...` spreads the "
               "study's runs over N ranks: the same files,\nwritten by rank 0 (docs/scaling.md).");
    TwoSpheresCommand twoSpheres(app);
    Cube27Command cube27(app);
    SlabCommand slab(app);
    TriaxialCommand triaxial(app);
    VerifyCommand verify(app);
    app.set_help_all_flag("--help-all", "print the help of every study and exit");
    if (argc < 2) {
        std::cerr << app.help();
        return 2;
    }
    return cli::runTool("lsdem-study", [&]() -> int {
        // CLI11 would call an unknown study an unexpected argument; name it as such.
        const std::string study = argv[1];
        const std::function<bool(const CLI::App*)> named = [&](const CLI::App* s) {
            return s->get_name() == study;
        };
        if (study[0] != '-' && std::as_const(app).get_subcommands(named).empty())
            throw Error("", "unknown study '" + study + "'",
                        "available: two-spheres, cube27, slab, triaxial, verify");
        if (const auto exitCode = cli::parse(app, argc, argv)) return *exitCode;
        if (twoSpheres.chosen()) return twoSpheres.run(*ranks);
        if (cube27.chosen()) return cube27.run(*ranks);
        if (triaxial.chosen()) return triaxial.run(*ranks);
        if (verify.chosen()) return verify.run(*ranks);
        return slab.run(*ranks);
    });
}
