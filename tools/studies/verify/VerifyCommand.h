/// @file VerifyCommand.h
/// @brief `lsdem-study verify`: the command line of the verification suite (VerifyStudy.h),
///        its table and its figures.
#pragma once

#include "studies/verify/VerifyStudy.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

class RunDistributor;

class VerifyCommand
{
public:
    /// Add `verify` to @a study, with its options, their defaults and the help.
    explicit VerifyCommand(CLI::App& study);
    VerifyCommand(const VerifyCommand&) = delete;  // the options point into mOptions
    VerifyCommand& operator=(const VerifyCommand&) = delete;

    bool chosen() const;

    /// Run the suite (rank 0 only: its cases are short), write DIR/verify_checks.csv and one
    /// CSV per figure, print the table and draw the figures. Returns the exit code: 0 every
    /// check passed, 5 some did not (the table says which), 4 the plots failed.
    int run(RunDistributor& ranks) const;

private:
    CLI::App* mCommand = nullptr;
    verify::VerifyOptions mOptions;
    long long mThreads = 0;
};

} // namespace lsdem
