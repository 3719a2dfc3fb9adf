/// @file ThreadLimit.h
/// @brief How many worker threads this process uses while a study runs: the user's number, or
///        under MPI the cores of the machine shared among the ranks on it (so that N ranks on
///        one machine do not each start a thread per core), or all cores.
#pragma once

#include <memory>
#include <string>

namespace lsdem {

class RunDistributor;

class ThreadLimit
{
public:
    /// @a requested threads if > 0; else ranks.threadsPerRank() if > 0; else no limit.
    ThreadLimit(long long requested, const RunDistributor& ranks);
    ~ThreadLimit();
    ThreadLimit(const ThreadLimit&) = delete;
    ThreadLimit& operator=(const ThreadLimit&) = delete;

    /// The limit in force, 0 for none (TBB's default: every core this process may use).
    long long threads() const { return mThreads; }

private:
    struct Control;
    std::unique_ptr<Control> mControl;
    long long mThreads = 0;
};

/// "spread over 3 ranks x 1 thread" (or "x all cores"), for a study's header line.
std::string describeRanks(const RunDistributor& ranks, const ThreadLimit& threads);

} // namespace lsdem
