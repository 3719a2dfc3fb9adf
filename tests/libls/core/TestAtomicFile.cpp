// Atomic output files: the new file appears whole, a failing writer leaves the old file and no
// temporary behind, and folders that are missing or cannot be folders are errors that name the
// path. Tests run as root in CI, where permission bits do not stop writes, so "cannot write"
// is made with a path under a regular file instead of chmod.
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

using namespace lsdem;
namespace fs = std::filesystem;

namespace {

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void writePlain(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

struct WriterFailed : std::runtime_error
{
    WriterFailed() : std::runtime_error("writer failed") {}
};

} // namespace

TEST(AtomicFile, TextFileIsCreatedAndReplacedWhole)
{
    test::ScratchDir dir;
    const std::string path = dir.file("out.csv");
    writeTextFileAtomically(path, "a,b\n1,2\n");
    EXPECT_EQ(readFile(path), "a,b\n1,2\n");
    const std::string binary("x\0y\n\xff", 5);  // bytes as given, no text conversion
    writeTextFileAtomically(path, binary);
    EXPECT_EQ(readFile(path), binary);
    writeTextFileAtomically(dir.file("empty.txt"), "");
    EXPECT_TRUE(fs::exists(dir.file("empty.txt")));
    EXPECT_EQ(fs::file_size(dir.file("empty.txt")), 0u);
    EXPECT_EQ(dir.entryCount(), 2u);
}

// The writer gets a hidden temporary in the target's folder (so the rename stays on one file
// system); the target appears only when the writer returns.
TEST(AtomicFile, WriterGetsATemporaryBesideTheTarget)
{
    test::ScratchDir dir;
    const std::string path = dir.file("result.txt");
    writePlain(path, "old");
    std::string seen;
    writeFileAtomically(path, [&](const std::string& tmp) {
        seen = tmp;
        EXPECT_EQ(fs::path(tmp).parent_path(), dir.path());
        EXPECT_EQ(fs::path(tmp).filename().string().rfind(".result.txt.tmp", 0), 0u) << tmp;
        writePlain(tmp, "new");
        EXPECT_EQ(readFile(path), "old");  // not yet replaced
    });
    EXPECT_EQ(readFile(path), "new");
    EXPECT_FALSE(fs::exists(seen));
    EXPECT_EQ(dir.entryCount(), 1u);
}

TEST(AtomicFile, ThrowingWriterLeavesTheOldFileAndNoTemporary)
{
    test::ScratchDir dir;
    const std::string path = dir.file("state.bin");
    writePlain(path, "previous contents");
    EXPECT_THROW(writeFileAtomically(path,
                                     [](const std::string& tmp) {
                                         writePlain(tmp, "half");
                                         throw WriterFailed();
                                     }),
                 WriterFailed);  // the writer's own exception passes on
    EXPECT_EQ(readFile(path), "previous contents");
    EXPECT_EQ(dir.entryCount(), 1u);

    EXPECT_THROW(writeStreamAtomically(path,
                                       [](std::ostream& out) {
                                           out << "partial";
                                           throw WriterFailed();
                                       }),
                 WriterFailed);
    EXPECT_EQ(readFile(path), "previous contents");
    EXPECT_EQ(dir.entryCount(), 1u);

    // A stream that goes bad while writing (as on a full disk) is an Error naming the file.
    try {
        writeStreamAtomically(path, [](std::ostream& out) {
            out << "partial";
            out.setstate(std::ios::badbit);
        });
        FAIL() << "a failed stream was not reported";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), path);
    }
    EXPECT_EQ(readFile(path), "previous contents");
    EXPECT_EQ(dir.entryCount(), 1u);

    // A writer that writes nothing: the rename fails, which is an Error, and nothing changes.
    EXPECT_THROW(writeFileAtomically(path, [](const std::string&) {}), Error);
    EXPECT_EQ(readFile(path), "previous contents");
    EXPECT_EQ(dir.entryCount(), 1u);
}

TEST(AtomicFile, MissingFoldersAndFoldersThatCannotExistAreErrors)
{
    test::ScratchDir dir;
    bool called = false;
    const auto writer = [&](const std::string&) { called = true; };
    // The folder does not exist: refused before the writer runs.
    try {
        writeFileAtomically(dir.file("missing/out.txt"), writer);
        FAIL() << "no error for a missing folder";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), dir.file("missing/out.txt"));
        EXPECT_NE(e.problem().find("does not exist"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(called);
    EXPECT_FALSE(fs::exists(dir.file("missing")));  // not created behind the user's back

    // The "folder" is a regular file: it can hold nothing (this also stands in for an
    // unwritable folder, which root could write anyway).
    writePlain(dir.file("plain"), "I am a file");
    EXPECT_THROW(writeTextFileAtomically(dir.file("plain/out.txt"), "x"), Error);
    EXPECT_EQ(readFile(dir.file("plain")), "I am a file");

    // The target is a folder.
    fs::create_directory(dir.file("sub"));
    try {
        writeTextFileAtomically(dir.file("sub"), "x");
        FAIL() << "no error for a folder as the target";
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("folder"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_directory(dir.file("sub")));
    EXPECT_EQ(dir.entryCount(), 2u);
}

TEST(AtomicFile, PrepareOutputFolderCreatesParentsOrExplains)
{
    test::ScratchDir dir;
    const std::string nested = dir.file("a/b/c");
    prepareOutputFolder(nested, "choose another --out");
    EXPECT_TRUE(fs::is_directory(nested));
    prepareOutputFolder(nested, "choose another --out");  // an existing folder is fine
    writeTextFileAtomically(nested + "/x.txt", "ok");
    EXPECT_EQ(readFile(nested + "/x.txt"), "ok");

    writePlain(dir.file("plain"), "I am a file");
    for (const std::string& bad : {dir.file("plain"), dir.file("plain/sub")}) {
        try {
            prepareOutputFolder(bad, "choose another --out");
            FAIL() << "no error for " << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), bad);
            EXPECT_EQ(e.fix(), "choose another --out");
        }
    }
    EXPECT_EQ(readFile(dir.file("plain")), "I am a file");
}
