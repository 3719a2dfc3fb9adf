/// @file SlabCommand.h
/// @brief `lsdem-study slab`: the command line of the interlocked-slab study (SlabStudy.h).
#pragma once

#include "common/CommandLine.h"

#include <string>

namespace lsdem {

/// `lsdem-study slab`'s help text.
const char* slabUsage();

/// `lsdem-study slab [options]`: parse @a args, print the cost, run, write the outputs and
/// draw the plots with @a plotDir/slab.py. Returns the exit code (4: plots failed).
int runSlabCommand(cli::Arguments& args, const std::string& plotDir);

} // namespace lsdem
