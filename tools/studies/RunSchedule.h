/// @file RunSchedule.h
/// @brief In which order a study's independent runs are handed out to the ranks, and how long
///        that takes: largest first, each to the first rank that is free (the longest-processing-
///        time rule, which keeps the ranks finishing close together).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace lsdem {

/// Indices of @a costs, largest cost first; equal costs keep their order.
std::vector<size_t> largestFirst(const std::vector<double>& costs);

/// The time @a ranks ranks take for runs of durations @a costs handed out largest first, each
/// to the rank that is free first: the largest finishing time. One rank: the sum; as many
/// ranks as runs: the largest run. 0 for no runs. @a ranks < 1 counts as 1.
double largestFirstMakespan(const std::vector<double>& costs, int ranks);

/// How many runs each rank did, for the summary of a study spread over ranks.
class RunShares
{
public:
    explicit RunShares(int ranks) : mRuns(size_t(ranks > 0 ? ranks : 1), 0) {}
    void add(int rank) { ++mRuns.at(size_t(rank)); }
    /// "7 runs over 3 ranks (runs per rank: 3 2 2)".
    std::string text() const;

private:
    std::vector<int> mRuns;
};

} // namespace lsdem
