/// @file TestSupport.h
/// @brief Small helpers shared by lsdem's tests: scratch folders, running the real command-line
///        programs, and reference values computed independently of the code under test.
#pragma once

#include "lsdem/core/Constants.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace lsdem::test {

/// A fresh folder under the system temp dir, removed when the object dies.
class ScratchDir
{
public:
    ScratchDir()
    {
        std::random_device rd;
        mPath = std::filesystem::temp_directory_path() /
                ("lsdem-test-" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(mPath);
    }
    ~ScratchDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(mPath, ec);
    }
    std::string file(const std::string& name) const { return (mPath / name).string(); }
    const std::filesystem::path& path() const { return mPath; }
    /// Number of entries in the folder (to check that nothing half-written was left).
    size_t entryCount() const
    {
        size_t n = 0;
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(mPath)) ++n;
        return n;
    }

private:
    std::filesystem::path mPath;
};

struct CommandResult
{
    int exitCode = -1;
    std::string output;  ///< stdout and stderr together
};

/// Run @a command through the shell, capturing stdout+stderr and the exit code.
inline CommandResult runCommand(const std::string& command)
{
    CommandResult result;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer{};
    size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        result.output.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// The whole content of the file at @a path, byte for byte ("" if it cannot be read).
inline std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace lsdem::test
