#include "common/PlotScripts.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

extern char** environ;

namespace lsdem::cli {

namespace {

/// How a program run by runProgram ended.
struct ProgramEnd
{
    int spawnError = 0;  ///< errno if it could not be started (ENOENT: no such program)
    int waitStatus = 0;  ///< as waitpid reports it, if it started
    bool succeeded() const
    {
        return spawnError == 0 && WIFEXITED(waitStatus) && WEXITSTATUS(waitStatus) == 0;
    }
};

/// Run @a argv (argv[0] searched on the PATH unless it holds a '/') and wait for it. No shell:
/// each element reaches the program as one argument, quotes and `$(...)` included. With
/// @a quiet, its stdout and stderr go to /dev/null.
ProgramEnd runProgram(const std::vector<std::string>& argv, bool quiet)
{
    std::vector<char*> pointers;
    for (const std::string& a : argv) pointers.push_back(const_cast<char*>(a.c_str()));
    pointers.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (quiet) {
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    ProgramEnd end;
    pid_t child = 0;
    end.spawnError =
        posix_spawnp(&child, pointers[0], &actions, nullptr, pointers.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (end.spawnError != 0) return end;
    while (::waitpid(child, &end.waitStatus, 0) < 0) {
        if (errno != EINTR) {
            end.spawnError = errno;
            break;
        }
    }
    return end;
}

/// "exit status 2" or "killed by signal 9", for a warning.
std::string describeEnd(const ProgramEnd& end)
{
    if (end.spawnError != 0) return std::strerror(end.spawnError);
    if (WIFEXITED(end.waitStatus))
        return "exit status " + std::to_string(WEXITSTATUS(end.waitStatus));
    if (WIFSIGNALED(end.waitStatus))
        return "killed by signal " + std::to_string(WTERMSIG(end.waitStatus));
    return "wait status " + std::to_string(end.waitStatus);
}

} // namespace

std::string plotScriptFolder()
{
    if (const char* fromEnvironment = std::getenv("LSDEM_PLOT_DIR");
        fromEnvironment && *fromEnvironment)
        return fromEnvironment;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return "";
    return (exe.parent_path().parent_path() / "share" / "lsdem" / "plots").string();
}

int drawPlots(const std::string& scriptName, const std::vector<std::string>& arguments)
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
    std::vector<std::string> command = {python, script};
    command.insert(command.end(), arguments.begin(), arguments.end());
    std::fflush(stdout);  // before the plotting process writes to the same stream
    std::fflush(stderr);
    const ProgramEnd end = runProgram(command, false);
    if (end.succeeded()) return 0;
    // Asked only now, so a working setup pays nothing: is it the missing matplotlib (the
    // usual case, with its usual fix) or the script itself?
    const bool noMatplotlib =
        end.spawnError == ENOENT ||
        !runProgram({python, "-c", "import matplotlib"}, true).succeeded();
    if (noMatplotlib) {
        std::fprintf(stderr, "lsdem-study: warning: plotting failed (needs /usr/bin/python3 with "
                             "python3-matplotlib); the data files are complete\n");
        return 4;
    }
    std::fprintf(stderr, "lsdem-study: warning: the plot script %s failed (%s); the data files "
                         "are complete\n",
                 script.c_str(), describeEnd(end).c_str());
    return 4;
}

} // namespace lsdem::cli
