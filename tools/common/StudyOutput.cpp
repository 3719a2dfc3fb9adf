#include "common/StudyOutput.h"

#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Error.h"

#include <unistd.h>

#include <filesystem>

namespace lsdem::cli {

namespace {

const char* const kFix = "choose another --out";

} // namespace

void checkOutputFolder(const std::string& dir)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    // The folder, or the nearest parent that exists: create_directories would start there.
    fs::path existing = fs::absolute(dir, ec);
    while (!fs::exists(existing, ec) && existing.has_relative_path())
        existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        throw Error(dir, "cannot create the output folder: '" + existing.string() +
                             "' is not a folder", kFix);
    if (::access(existing.c_str(), W_OK | X_OK) != 0)
        throw Error(dir, "the output folder " +
                             (fs::exists(dir, ec) ? std::string("is not writable")
                                                  : "cannot be created in '" + existing.string() +
                                                        "' (not writable)"),
                    kFix);
}

void prepareOutputFolder(const std::string& dir)
{
    lsdem::prepareOutputFolder(dir, kFix);
}

} // namespace lsdem::cli
