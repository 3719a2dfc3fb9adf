/// @file FolderLock.h
/// @brief An advisory lock on a folder, so that two programs never write one output folder at
///        once (nor one reads a checkpoint there while another replaces it). It is flock(2) on
///        the folder itself: no lock file is left in it, and the system drops the lock when
///        its holder ends, however it ends (kill -9 too), so it never goes stale.
#pragma once

#include <string>

namespace lsdem {

class FolderLock
{
public:
    /// Shared: to read the folder (any number at once); exclusive: to write it (alone).
    enum class Mode { Shared, Exclusive };

    FolderLock() = default;
    ~FolderLock() { unlock(); }
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

    /// Lock @a dir in @a mode without waiting (a lock held before is dropped first). False if
    /// another holder's lock conflicts. Where no lock can be taken (a missing folder, a file
    /// system without flock) it is true and nothing is held: the lock is a safeguard, never a
    /// reason to refuse work.
    bool tryLock(const std::string& dir, Mode mode);
    void unlock();

private:
    int mFd = -1;
};

} // namespace lsdem
