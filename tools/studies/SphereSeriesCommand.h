/// @file SphereSeriesCommand.h
/// @brief The command-line options the two sphere studies (`lsdem-study two-spheres`,
///        `lsdem-study cube27`) share, read into SphereSeriesOptions.
#pragma once

#include "studies/SphereSeriesOptions.h"

namespace CLI {
class App;
} // namespace CLI

namespace lsdem {

/// Add to @a command the options of SphereSeriesOptions, reading into @a o, in the help groups
/// "Contact model" and "Spheres"; the help shows @a o's values as the defaults. Not added:
/// --delta-max, whose meaning differs between the studies, and the output options
/// (addOutputOptions).
void addSphereSeriesOptions(CLI::App& command, SphereSeriesOptions& o);

} // namespace lsdem
