#include "common/StudyOutput.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"

#include <fnmatch.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

namespace lsdem::cli {

namespace {

const char* const kFix = "choose another --out";

/// Remove the files (and links) of @a folder whose names match @a pattern; the count.
int removeMatching(const std::filesystem::path& folder, const std::string& pattern)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return 0;
    int removed = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
        const fs::file_type type = e.symlink_status(ec).type();
        if (type != fs::file_type::regular && type != fs::file_type::symlink) continue;
        if (::fnmatch(pattern.c_str(), e.path().filename().c_str(), 0) != 0) continue;
        removeEarlierRunFile(e.path().string());
        ++removed;
    }
    return removed;
}

} // namespace

void removeEarlierRunFile(const std::string& file)
{
    std::error_code ec;
    std::filesystem::remove(file, ec);
    if (ec)
        throw Error(file, "cannot remove this file of an earlier run (" + ec.message() + ")", kFix);
}

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

void prepareOutputFolder(const std::string& dir, const StudyFiles& ownFiles, bool quiet)
{
    lsdem::prepareOutputFolder(dir, kFix);
    int removed = 0;
    for (const std::string& own : ownFiles) {
        const std::filesystem::path relative(own);
        removed += removeMatching(std::filesystem::path(dir) / relative.parent_path(),
                                  relative.filename().string());
    }
    if (removed > 0 && !quiet)
        std::printf("removed %d file%s of an earlier run from %s\n", removed,
                    removed == 1 ? "" : "s", dir.c_str());
}

} // namespace lsdem::cli
