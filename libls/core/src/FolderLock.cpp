#include "lsdem/core/FolderLock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>

namespace lsdem {

bool FolderLock::tryLock(const std::string& dir, Mode mode)
{
    unlock();
    mFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (mFd < 0) return true;
    if (::flock(mFd, (mode == Mode::Shared ? LOCK_SH : LOCK_EX) | LOCK_NB) == 0) return true;
    const bool busy = errno == EWOULDBLOCK;
    unlock();
    return !busy;
}

void FolderLock::unlock()
{
    if (mFd < 0) return;
    ::close(mFd);  // drops the lock
    mFd = -1;
}

} // namespace lsdem
