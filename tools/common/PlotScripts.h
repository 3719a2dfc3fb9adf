/// @file PlotScripts.h
/// @brief Where lsdem-study finds its matplotlib scripts, and how it runs them: found from the
///        program's own path, so no source path is compiled into it and an installed copy works
///        anywhere; run without a shell, so any output folder name reaches a script as it is.
#pragma once

#include <string>
#include <vector>

namespace lsdem::cli {

/// The folder of the plot scripts: $LSDEM_PLOT_DIR if set and not empty, otherwise
/// <folder of this executable>/../share/lsdem/plots. That is <prefix>/share/lsdem/plots for a
/// program installed in <prefix>/bin, and <build>/share/lsdem/plots (where the build copies
/// tools/plots) for one run from <build>/tools. "" if the executable's path is unknown.
std::string plotScriptFolder();

/// Run the matplotlib script @a scriptName (found with plotScriptFolder) with @a arguments,
/// each passed to it as one argument, whatever characters it holds (no shell in between).
/// Debian's /usr/bin/python3 is preferred: a pyenv python on the PATH usually lacks
/// python3-matplotlib. Returns 0 on success; otherwise prints a warning saying why (no
/// script, no python3 with matplotlib, or the script's exit status; the data files are
/// complete) and returns 4, the tools' exit code for "results written, plots missing".
int drawPlots(const std::string& scriptName, const std::vector<std::string>& arguments);

} // namespace lsdem::cli
