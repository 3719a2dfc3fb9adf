#include "lsdem/core/AtomicFile.h"

#include "lsdem/core/Error.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace lsdem {

namespace {

fs::path folderOf(const fs::path& file)
{
    return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

} // namespace

void checkOutputFile(const std::string& path)
{
    const fs::path target(path);
    const fs::path folder = folderOf(target);
    std::error_code ec;
    if (!fs::exists(folder, ec))
        throw Error(path, "the output folder '" + folder.string() + "' does not exist",
                    "create it first or choose another output path");
    if (!fs::is_directory(folder, ec))
        throw Error(path, "'" + folder.string() + "' is a file, not a folder",
                    "choose another output path");
    if (::access(folder.c_str(), W_OK) != 0)
        throw Error(path, "the output folder '" + folder.string() + "' is not writable",
                    "choose a folder you can write to");
    if (fs::is_directory(target, ec))
        throw Error(path, "the output path is a folder", "give a file name");
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tmpPath)>& writeTo)
{
    checkOutputFile(path);
    const fs::path target(path);
    const fs::path folder = folderOf(target);
    std::error_code ec;

    // A unique temporary beside the target, so the final rename never crosses file systems.
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = folder / ("." + target.filename().string() + ".tmp-" +
                                   std::to_string(::getpid()) + "-" +
                                   std::to_string(counter++));
    try {
        writeTo(tmp.string());
        fs::rename(tmp, target);
    } catch (const fs::filesystem_error& e) {
        fs::remove(tmp, ec);
        throw Error(path, std::string("could not write the file: ") + e.what());
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
}

void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream& out)>& write)
{
    writeFileAtomically(path, [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error(path, "cannot create a temporary file beside it",
                        "check that the folder is writable and not full");
        write(out);
        out.close();
        if (!out)
            throw Error(path, "could not write the file (disk full?)",
                        "free some disk space or choose another output folder");
    });
}

void writeTextFileAtomically(const std::string& path, const std::string& contents)
{
    writeStreamAtomically(path, [&](std::ostream& out) {
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    });
}

void prepareOutputFolder(const std::string& dir, const std::string& fix)
{
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw Error(dir, "cannot create the output folder (" + ec.message() + ")", fix);
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(dir, "the output folder is not writable", fix);
}

} // namespace lsdem
