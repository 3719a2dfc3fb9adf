#include "studies/SphereSeriesCommand.h"

#include "studies/StudyCommandOptions.h"

#include "common/CommandLine.h"

#include <CLI/CLI.hpp>

namespace lsdem {

void addSphereSeriesOptions(CLI::App& command, SphereSeriesOptions& o)
{
    using cli::addCounts;
    using cli::addInteger;
    using cli::addNumber;
    using cli::addNumbers;
    const std::string model = "Contact model";
    addFormulationOption(command, o.formulations)->group(model);
    addNumbers(command, "--kn", o.stiffness,
               "stiffnesses for every formulation (default: the paper's,\n"
               "kn = 1e9 N/mm for original/single-node, kn* = 1e3 N/mm^3 for\n"
               "adapted/volume, and the --k-factors series of that at the node\n"
               "count nearest --k-nodes)")
        ->type_name("K")
        ->group(model);
    addNumbers(command, "--k-factors", o.stiffnessFactors, "the stiffness series factors")
        ->type_name("F")
        ->group(model);
    addInteger(command, "--k-nodes", o.kSeriesNodes, "node count of the stiffness series")
        ->type_name("N")
        ->group(model);
    addTestingOption(command, o.testing)->group(model);

    const std::string spheres = "Spheres";
    addCounts(command, "--nodes", o.nodeCounts, "node counts")->type_name("N")->group(spheres);
    addNumber(command, "--radius", o.radius, "sphere radius, mm")->type_name("R")->group(spheres);
    addNumber(command, "--voxel", o.voxel, "level-set voxel size, mm")
        ->type_name("VDP")
        ->group(spheres);
    addInteger(command, "--orientations", o.orientations, "random orientation sets averaged")
        ->type_name("M")
        ->group(spheres);
    command
        .add_option_function<std::string>(
            "--seed",
            [&o](const std::string& text) {
                // Wrapped into unsigned as it always was, so a seed gives the same orientations.
                o.seed = unsigned(cli::parseInteger(text, "--seed"));
            },
            "seed of the orientations")
        ->type_name("S")
        ->default_str(std::to_string(o.seed))
        ->group(spheres);
}

} // namespace lsdem
