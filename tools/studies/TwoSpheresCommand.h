/// @file TwoSpheresCommand.h
/// @brief `lsdem-study two-spheres`: the command line of the two-sphere study
///        (TwoSpheresStudy.h), its summary and plots.
#pragma once

#include "studies/TwoSpheresStudy.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

class TwoSpheresCommand
{
public:
    /// Add `two-spheres` to @a study, with its options, their defaults and the help.
    explicit TwoSpheresCommand(CLI::App& study);
    TwoSpheresCommand(const TwoSpheresCommand&) = delete;  // the options point into mOptions
    TwoSpheresCommand& operator=(const TwoSpheresCommand&) = delete;

    /// Whether the parsed command line chose this study.
    bool chosen() const;

    /// Check the options, run the study with its runs spread by @a ranks, write
    /// DIR/two_spheres.csv, print the summary and draw the plots (rank 0; the other ranks only
    /// do runs). Returns the exit code (4: the plots failed). @throw Error for bad options.
    int run(RunDistributor& ranks) const;

private:
    CLI::App* mCommand = nullptr;
    TwoSpheresOptions mOptions;
};

} // namespace lsdem
