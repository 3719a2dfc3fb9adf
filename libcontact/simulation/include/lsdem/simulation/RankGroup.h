/// @file RankGroup.h
/// @brief The processes one simulation is split over (the ranks of an MPI job), as the
///        simulation needs them: who am I, how many are we, and three collective operations.
///        MPI itself stays out of the libraries: lsdem-run gives an MPI implementation
///        (tools/run/MpiRankGroup.cpp, built only with MPI); tests may give one of threads.
///
/// Every member is collective: each rank of the group calls it, in the same order.
#pragma once

#include <cstddef>
#include <vector>

namespace lsdem {

class RankGroup
{
public:
    virtual ~RankGroup() = default;

    virtual int rank() const = 0;
    virtual int ranks() const = 0;
    bool isRoot() const { return rank() == 0; }

    /// Every rank's @a mine, one after the other in rank order, into @a all; rank r's bytes
    /// are [starts[r], starts[r + 1]) (@a starts gets ranks() + 1 entries).
    virtual void allGather(const std::vector<char>& mine, std::vector<char>& all,
                           std::vector<size_t>& starts) = 0;

    /// @a toEach[r] to rank r, for every r (itself included), and from every rank r its bytes
    /// for this one into @a received at [starts[r], starts[r + 1]) (@a starts gets ranks() + 1
    /// entries). The exchange of ghosts and migrating grains (GhostDecomposition.h).
    virtual void allToAll(const std::vector<std::vector<char>>& toEach,
                          std::vector<char>& received, std::vector<size_t>& starts) = 0;

    /// Whether @a mine is true on any rank (a stop request that reached one rank only).
    virtual bool anyRank(bool mine) = 0;
};

} // namespace lsdem
