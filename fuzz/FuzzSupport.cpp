#include "FuzzSupport.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace lsdem::fuzz {

namespace {

/// The process's scratch folder, made on first use and removed at exit.
class ScratchFolder
{
public:
    ScratchFolder()
    {
        std::error_code ec;
        const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                                                                : fs::temp_directory_path();
        std::string pattern = (base / "lsdem-fuzz-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) {
            std::perror("lsdem fuzz: cannot make a scratch folder");
            std::abort();
        }
        mPath = pattern;
    }
    ~ScratchFolder()
    {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    const fs::path& path() const { return mPath; }

private:
    fs::path mPath;
};

} // namespace

std::string writeScratchFile(const std::uint8_t* data, std::size_t size,
                             const std::string& extension)
{
    static const ScratchFolder folder;
    const std::string path = (folder.path() / ("input" + extension)).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
        std::fprintf(stderr, "lsdem fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
    return path;
}

void requireClearError(const Error& error)
{
    if (error.where().empty() || error.problem().empty()) {
        std::fprintf(stderr, "lsdem fuzz: an Error without a place or a problem: '%s'\n",
                     error.what());
        std::abort();
    }
}

} // namespace lsdem::fuzz
