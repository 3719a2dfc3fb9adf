/// @file StudyOutput.h
/// @brief What every study driver does around its run: make sure the output folder can be
///        written before any work starts, and draw the plots with Debian's matplotlib.
#pragma once

#include "common/PlotScripts.h"

#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Error.h"

#include <string>

namespace lsdem::cli {

/// Create @a dir (and its parents) and check that it is writable; an Error naming it otherwise.
inline void prepareOutputFolder(const std::string& dir)
{
    lsdem::prepareOutputFolder(dir, "choose another --out");
}

} // namespace lsdem::cli
