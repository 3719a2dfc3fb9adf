#include "studies/StudyCommandOptions.h"

#include "common/CommandLine.h"

#include <CLI/CLI.hpp>

namespace lsdem {

CLI::Option* addFormulationOption(CLI::App& command, std::vector<Formulation>& formulations)
{
    std::vector<std::string> names;
    for (Formulation f : formulations) names.push_back(formulationName(f));
    return cli::lastListWins(
               command.add_option_function<std::vector<std::string>>(
                   "--formulation",
                   [&formulations](const std::vector<std::string>& given) {
                       formulations.clear();
                       for (const std::string& name : given)
                           formulations.push_back(parseFormulation(name));
                   },
                   "original, adapted, single-node, volume"))
        ->type_name("F")
        ->default_str(cli::showList(names));
}

CLI::Option* addTestingOption(CLI::App& command, NodeTesting& testing)
{
    return command
        .add_option_function<std::string>(
            "--testing", [&testing](const std::string& name) { testing = parseNodeTesting(name); },
            "symmetric (both grains' nodes tested) or one-way (the smaller's)")
        ->type_name("T")
        ->default_str(nodeTestingName(testing));
}

void addOutputOptions(CLI::App& command, std::string& outDir, bool& plots, bool& quiet,
                      const std::string& quietHelp)
{
    const std::string group = "Output";
    command.add_option("--out", outDir,
                       "output folder (created if missing; the files this study wrote\n"
                       "there in an earlier run are replaced, other files kept)")
        ->type_name("DIR")
        ->capture_default_str()
        ->group(group);
    command.add_flag_callback("--no-plots", [&plots] { plots = false; },
                              "write the data files only, no plots")
        ->group(group);
    command.add_flag("-q,--quiet", quiet, quietHelp)->group(group);
}

} // namespace lsdem
