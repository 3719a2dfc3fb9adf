/// @file StudyCommandOptions.h
/// @brief The options every `lsdem-study` command has: the formulations to run, how nodes are
///        tested, where the outputs go and how much is printed.
#pragma once

#include "lsdem/contact/ContactModel.h"

#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
} // namespace CLI

namespace lsdem {

/// `--formulation F...`: the formulations to run, replacing @a formulations (whose current
/// value is shown as the default). A name that is not a formulation is an Error.
CLI::Option* addFormulationOption(CLI::App& command, std::vector<Formulation>& formulations);

/// `--testing T`: symmetric or one-way node testing into @a testing.
CLI::Option* addTestingOption(CLI::App& command, NodeTesting& testing);

/// `--out DIR` into @a outDir, `--no-plots` (clears @a plots) and `-q, --quiet` into @a quiet,
/// whose help is @a quietHelp; in the help group "Output".
void addOutputOptions(CLI::App& command, std::string& outDir, bool& plots, bool& quiet,
                      const std::string& quietHelp);

} // namespace lsdem
