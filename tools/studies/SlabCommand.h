/// @file SlabCommand.h
/// @brief `lsdem-study slab`: the command line of the interlocked-slab study (SlabStudy.h), its
///        cost estimate, summary and plots.
#pragma once

#include "studies/SlabStudy.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

class SlabCommand
{
public:
    /// Add `slab` to @a study, with its options, their defaults and the help.
    explicit SlabCommand(CLI::App& study);
    SlabCommand(const SlabCommand&) = delete;  // the options point into this object
    SlabCommand& operator=(const SlabCommand&) = delete;

    /// Whether the parsed command line chose this study.
    bool chosen() const;

    /// Check the options, print the cost (and stop there with --estimate), run the study with
    /// its runs spread by @a ranks, write the outputs, print the summary and draw the plots
    /// (rank 0; the other ranks only do runs). Returns the exit code (4: the plots failed).
    /// @throw Error for bad options, before anything is written.
    int run(RunDistributor& ranks) const;

private:
    CLI::App* mCommand = nullptr;
    SlabStudyOptions mOptions;
    long long mThreads = 0;                ///< worker threads (0: all cores)
    bool mEstimateOnly = false;
};

} // namespace lsdem
