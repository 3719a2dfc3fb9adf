/// @file GhostDecomposition.h
/// @brief One simulation split over the ranks of a RankGroup by space (domain decomposition):
///        each rank owns the grains whose centres lie in its sub-domain and holds ghost copies
///        of the grains within reach of it; grains and their contact histories migrate to a
///        new owner when they cross. See docs/scaling.md.
///
/// The sub-domains are a recursive coordinate bisection (WorkBisection.h), weighted by the
/// node checks of each grain's contacts, redrawn when the ranks' work drifts out of balance.
/// A rank's world (World.h) holds its owned grains and its ghosts only, ordered by their
/// global index (the index of the whole simulation), so its contact list is the one-process
/// list restricted to the pairs with an owned grain, in the same order.
///
/// Ownership and the ghost sets change only when the contact list is rebuilt (every rank
/// rebuilds at the same step: the same rule as one process, voted over the ranks). A ghost is
/// every grain whose bounding sphere comes within the largest bounding radius plus the list's
/// skin of the sub-domain, so every pair on the list of an owned grain has both grains on the
/// rank until the next rebuild. Between rebuilds a grain keeps its owner even if its centre has
/// crossed (by less than half the skin).
///
/// A pair whose grains have different owners is evaluated by both ("newton off"): the contact
/// law is a function of the two grains' states and the pair's shear history, so both get the
/// same bits and keep identical histories, and each owner sums its grain's contacts in the
/// one-process order, without sending forces back. Quantities summed over all grains or
/// contacts (boundary reactions, energies) are gathered as keyed terms and summed in the
/// one-process order (gatherSorted), so every output is bit for bit that of one process.
#pragma once

#include "lsdem/simulation/ContactList.h"
#include "lsdem/simulation/RankGroup.h"
#include "lsdem/simulation/WorkBisection.h"

#include <map>
#include <vector>

namespace lsdem {

/// What the decomposition did, summed over the run (bytes to and from other ranks only).
struct GhostCounters
{
    double exchangeSeconds = 0.0;  ///< in collective calls (waiting for other ranks included)
    double packSeconds = 0.0;      ///< packing and unpacking
    long long bytesSent = 0, bytesReceived = 0;
    long long ghostUpdates = 0;    ///< per-step exchanges of ghost states
    long long redistributions = 0; ///< exchanges of grains and histories at list rebuilds
    long long rebalances = 0;      ///< redraws of the sub-domains
    long long grainsMigrated = 0;  ///< grains this rank received as owner from another rank
    long long grainsEmigrated = 0; ///< grains this rank owned and handed to another rank
    long long historiesMigrated = 0;  ///< non-empty shear histories received from other ranks
    long long sumsGathered = 0;    ///< gatherSorted calls
    int owned = 0, ghosts = 0;     ///< at the last redistribution
    double lastImbalance = 1.0;    ///< max / mean of the ranks' work at the last redistribution
};

/// A term of a sum over the whole simulation, ordered by its key as one process orders it.
struct OrderedTerm
{
    long long key[3] = {0, 0, 0};
    double value[5] = {0, 0, 0, 0, 0};
};

class GhostDecomposition
{
public:
    /// @param ranks the group (outlives this); its rank() is this process
    /// @param rebalanceAbove redraw the sub-domains when max / mean of the ranks' work exceeds
    ///        this (and the best split of the last redraw by the same factor), at a list
    ///        rebuild at least 50 evaluations after the last redraw
    explicit GhostDecomposition(RankGroup& ranks, double rebalanceAbove = 1.1);

    RankGroup& ranks() { return mRanks; }
    int rank() const { return mRanks.rank(); }
    int rankCount() const { return mRanks.ranks(); }

    /// Collective. @a world is the whole simulation, the same on every rank (built from the
    /// scene or a checkpoint); keep this rank's part of it: the grains whose centres lie in
    /// its sub-domain (a bisection by grain count) and their ghosts, and the histories of
    /// their contacts. @a skin is the contact list's.
    void distribute(World& world, double skin);

    /// Collective, when the contact list is about to be rebuilt: grains whose centres left
    /// this rank's sub-domain go to their new owner with their contact histories, the
    /// sub-domains are redrawn if the work drifted, and the ghost sets are drawn anew. The
    /// world's grains are renumbered (its contact list must be rebuilt): renumbering() says how.
    void redistribute(World& world);
    /// After redistribute(): the new index of each grain of this rank's world before it (-1:
    /// no longer here).
    const std::vector<int>& renumbering() const { return mRenumbering; }

    /// Collective, before an evaluation: every ghost takes its owner's pose and velocities;
    /// and the vote on a rebuild of the contact lists, carried along (one exchange a step):
    /// @return whether @a rebuildHere is true on any rank.
    bool updateGhosts(World& world, bool rebuildHere = false);

    /// After an evaluation: the work of each owned grain (1 + the node checks of the contacts
    /// it is the first grain of), for the next balance.
    void recordWork(const ContactList& contacts);

    /// Per grain of this rank's world: whether this rank owns it (else it is a ghost).
    const std::vector<char>& owned() const { return mOwned; }
    /// Per grain of this rank's world: its index in the whole simulation (ascending).
    const std::vector<int>& globalIds() const { return mGlobal; }
    /// Grains in the whole simulation.
    int globalCount() const { return mGlobalCount; }

    /// Collective: every rank's @a mine, sorted by key (every key must be on one rank only).
    std::vector<OrderedTerm> gatherSorted(const std::vector<OrderedTerm>& mine);

    /// Collective: the whole simulation as one process holds it (every grain in order, every
    /// contact history including the empty ones of the list), on rank 0 (the others get an
    /// empty world): for checkpoints, grains.csv and tests. @a local is this rank's world.
    World gatherWorld(const World& local);

    const WorkBisection& domains() const { return mDomains; }
    const GhostCounters& counters() const { return mCounters; }

private:
    /// Where each owned grain goes: its new owner and the ranks it is a ghost on.
    void route(const World& world, std::vector<int>& newOwner,
               std::vector<std::vector<int>>& ghostRanks) const;
    void maybeRebalance(const World& world);
    /// What a redistribution received: grains, pair and boundary histories (defined in
    /// GhostDecomposition.cpp).
    struct Inbox;
    /// A redistribution's phases: each owned grain (and its histories) packed for its new
    /// owner and ghost holders; what arrived, read; this rank's world rebuilt from it.
    void packMoves(const World& world, const std::vector<int>& newOwner,
                   const std::vector<std::vector<int>>& ghostRanks);
    void unpackMoves(const World& world, Inbox& inbox);
    void rebuildWorld(World& world, Inbox& inbox);
    void exchange(const std::vector<std::vector<char>>& toEach, std::vector<char>& received,
                  std::vector<size_t>& starts);
    int assetIndex(const World& world, const GrainAsset* asset) const;
    /// The index in this rank's world of global grain @a id, or -1.
    int localOf(int id) const;

    RankGroup& mRanks;
    double mRebalanceAbove;
    double mRedrawAbove = 0.0;
    WorkBisection mDomains;
    double mReach = 0.0;  ///< largest bounding radius + skin
    int mGlobalCount = 0;
    long long mEvaluations = 0, mLastRedraw = 0;
    std::vector<int> mGlobal;
    std::vector<int> mRenumbering;
    std::vector<char> mOwned;
    std::vector<double> mWork;  ///< per grain of this rank's world (owned ones meaningful)
    std::vector<std::vector<int>> mSendGhosts;     ///< per rank: our grains it holds as ghosts
    std::vector<std::vector<int>> mReceiveGhosts;  ///< per rank: its grains we hold as ghosts
    std::map<const GrainAsset*, int> mAssetIndex;
    std::vector<std::vector<char>> mToEach;
    std::vector<char> mReceived;
    std::vector<size_t> mStarts;
    GhostCounters mCounters;
};

} // namespace lsdem
