/// @file PlotScripts.h
/// @brief Where lsdem-study finds its matplotlib scripts: found from the program's own path, so
///        no source path is compiled into it and an installed copy works anywhere.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace lsdem::cli {

/// The folder of the plot scripts: $LSDEM_PLOT_DIR if set and not empty, otherwise
/// <folder of this executable>/../share/lsdem/plots. That is <prefix>/share/lsdem/plots for a
/// program installed in <prefix>/bin, and <build>/share/lsdem/plots (where the build copies
/// tools/plots) for one run from <build>/tools. "" if the executable's path is unknown.
inline std::string plotScriptFolder()
{
    if (const char* fromEnvironment = std::getenv("LSDEM_PLOT_DIR");
        fromEnvironment && *fromEnvironment)
        return fromEnvironment;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return "";
    return (exe.parent_path().parent_path() / "share" / "lsdem" / "plots").string();
}

} // namespace lsdem::cli
