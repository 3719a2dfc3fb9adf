/// lsdem-study: the paper's studies as one command each; writes CSV and PNG plots.

#include "common/CommandLine.h"
#include "studies/Cube27Command.h"
#include "studies/SlabCommand.h"
#include "studies/TwoSpheresCommand.h"

#include "lsdem/ls/Error.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <utility>

int main(int argc, char** argv)
{
    using namespace lsdem;
    CLI::App app("The studies of Feldfogel et al. (2024), one command each: CSV files and, with "
                 "python3-matplotlib,\nPNG plots in the --out folder.",
                 "lsdem-study");
    cli::applyConventions(app);
    app.require_subcommand(1, 1);
    app.footer("`lsdem-study STUDY --help` lists a study's options. Exit codes: 0 done, 1 bad "
               "input,\n2 no arguments (this help on stderr), 3 internal error, 4 results "
               "written but plots missing.");
    TwoSpheresCommand twoSpheres(app);
    Cube27Command cube27(app);
    SlabCommand slab(app);
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
                        "available: two-spheres, cube27, slab");
        if (const auto exitCode = cli::parse(app, argc, argv)) return *exitCode;
        if (twoSpheres.chosen()) return twoSpheres.run();
        if (cube27.chosen()) return cube27.run();
        return slab.run();
    });
}
