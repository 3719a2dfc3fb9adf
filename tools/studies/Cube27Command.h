/// @file Cube27Command.h
/// @brief `lsdem-study cube27`: the command line of the 27-sphere study (Cube27Study.h), its
///        summary and plots.
#pragma once

#include "studies/Cube27Study.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

class Cube27Command
{
public:
    /// Add `cube27` to @a study, with its options, their defaults and the help.
    explicit Cube27Command(CLI::App& study);
    Cube27Command(const Cube27Command&) = delete;  // the options point into mOptions
    Cube27Command& operator=(const Cube27Command&) = delete;

    /// Whether the parsed command line chose this study.
    bool chosen() const;

    /// Check the options and the loading plan, run the study, write DIR/cube27.csv, print the
    /// summary and draw the plots (rank 0; the other ranks of @a ranks only do runs). Returns
    /// the exit code (4: the plots failed). @throw Error for bad options, before anything is
    /// written.
    int run(RunDistributor& ranks) const;

private:
    CLI::App* mCommand = nullptr;
    Cube27Options mOptions;
};

} // namespace lsdem
