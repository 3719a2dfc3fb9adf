/// @file StudyOutput.h
/// @brief What every study driver does around its run: make sure the output folder can be
///        written before any work starts, and draw the plots with Debian's matplotlib.
#pragma once

#include "common/PlotScripts.h"

#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Error.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace lsdem::cli {

/// Create @a dir (and its parents) and check that it is writable; an Error naming it otherwise.
inline void prepareOutputFolder(const std::string& dir)
{
    lsdem::prepareOutputFolder(dir, "choose another --out");
}

/// Run the matplotlib script @a scriptName (found with plotScriptFolder) with @a arguments.
/// Debian's /usr/bin/python3 is preferred: a pyenv python on the PATH usually lacks
/// python3-matplotlib. Returns 0 on success; otherwise prints a warning (the data files are
/// complete) and returns 4, the tools' exit code for "results written, plots missing".
inline int drawPlots(const std::string& scriptName, const std::vector<std::string>& arguments)
{
    const std::string script = plotScriptFolder() + "/" + scriptName;
    if (!std::filesystem::is_regular_file(script)) {
        std::fprintf(stderr, "lsdem-study: warning: no plot script %s (set LSDEM_PLOT_DIR to the "
                             "folder of lsdem's plot scripts); the data files are complete\n",
                     script.c_str());
        return 4;
    }
    const std::string python =
        std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    std::string command = python + " '" + script + "'";
    for (const std::string& a : arguments) command += " '" + a + "'";
    std::fflush(stdout);  // before the plotting process writes to the same stream
    if (std::system(command.c_str()) == 0) return 0;
    std::fprintf(stderr, "lsdem-study: warning: plotting failed (needs /usr/bin/python3 with "
                         "python3-matplotlib); the data files are complete\n");
    return 4;
}

} // namespace lsdem::cli
