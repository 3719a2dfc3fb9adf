// Folder locks: one writer or any number of readers at a time, dropped with the lock object;
// no file is left in the folder, and where no lock can be taken nothing is refused. (flock
// locks belong to an open file, so two locks in one process conflict as two processes' do.)
#include "lsdem/core/FolderLock.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

using namespace lsdem;

TEST(FolderLock, OneWriterOrManyReaders)
{
    test::ScratchDir dir;
    const std::string folder = dir.path().string();
    using Mode = FolderLock::Mode;
    {
        FolderLock writer, other;
        ASSERT_TRUE(writer.tryLock(folder, Mode::Exclusive));
        EXPECT_FALSE(other.tryLock(folder, Mode::Exclusive));
        EXPECT_FALSE(other.tryLock(folder, Mode::Shared));
        writer.unlock();
        EXPECT_TRUE(other.tryLock(folder, Mode::Exclusive));
    }  // dropped with the objects
    FolderLock reader, secondReader, writer;
    ASSERT_TRUE(reader.tryLock(folder, Mode::Shared));
    EXPECT_TRUE(secondReader.tryLock(folder, Mode::Shared));
    EXPECT_FALSE(writer.tryLock(folder, Mode::Exclusive));
    reader.unlock();
    secondReader.unlock();
    EXPECT_TRUE(writer.tryLock(folder, Mode::Exclusive));
    EXPECT_EQ(dir.entryCount(), 0u);
}

TEST(FolderLock, AMissingFolderHoldsNothingAndRefusesNothing)
{
    test::ScratchDir dir;
    FolderLock a, b;
    EXPECT_TRUE(a.tryLock(dir.file("missing"), FolderLock::Mode::Exclusive));
    EXPECT_TRUE(b.tryLock(dir.file("missing"), FolderLock::Mode::Exclusive));
}
