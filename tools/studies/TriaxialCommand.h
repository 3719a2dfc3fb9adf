/// @file TriaxialCommand.h
/// @brief `lsdem-study triaxial`: the command line of the triaxial study (TriaxialStudy.h),
///        its files, summary and plots.
#pragma once

#include "studies/TriaxialOptions.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

class RunDistributor;

class TriaxialCommand
{
public:
    /// Add `triaxial` to @a study, with its options, their defaults and the help.
    explicit TriaxialCommand(CLI::App& study);
    TriaxialCommand(const TriaxialCommand&) = delete;  // the options point into mOptions
    TriaxialCommand& operator=(const TriaxialCommand&) = delete;

    bool chosen() const;

    /// Check the options, run the study with its runs spread by @a ranks, write
    /// DIR/triaxial.csv and DIR/triaxial_runs.csv, print the summary and draw the plots (rank
    /// 0). Returns the exit code (4: the plots failed). @throw Error for bad options.
    int run(RunDistributor& ranks) const;

private:
    CLI::App* mCommand = nullptr;
    TriaxialOptions mOptions;
};

} // namespace lsdem
