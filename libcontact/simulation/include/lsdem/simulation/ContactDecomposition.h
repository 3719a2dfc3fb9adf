/// @file ContactDecomposition.h
/// @brief One simulation's contacts split over the ranks of a RankGroup, every rank holding
///        the whole world (replicated state; see docs/scaling.md).
///
/// Each rank builds the same contact list (it is deterministic). Each slot belongs to the rank
/// whose sub-domain holds the centre of the slot's first grain; the sub-domains are a
/// recursive coordinate bisection (WorkBisection.h) of the grains' centres weighted by the
/// node checks of their slots at the last evaluation, redrawn when the work the ranks own
/// drifts out of balance. A rank evaluates its slots only; then every slot's result, counts,
/// point forces and shear history go to every rank (one all-gather of bytes), and each rank
/// sums and integrates all grains as a single process would, in the same fixed order. So the
/// state stays identical on every rank and bit for bit that of one process, for any rank and
/// thread count.
///
/// What this does not do (the next step): split the memory. Every rank holds every grain,
/// contact and history, and the all-gather carries every evaluated contact to every rank, so
/// its volume per rank grows with the whole simulation's contacts: a few ranks, not hundreds.
#pragma once

#include "lsdem/simulation/ContactList.h"
#include "lsdem/simulation/RankGroup.h"
#include "lsdem/simulation/WorkBisection.h"

#include <vector>

namespace lsdem {

/// What the decomposition did, summed over evaluations.
struct DecompositionCounters
{
    double exchangeSeconds = 0.0;  ///< in the all-gather (waiting for the other ranks included)
    double packSeconds = 0.0;      ///< packing and unpacking slot results
    long long bytesSent = 0;       ///< this rank's slot results (each sent once to the group)
    long long bytesReceived = 0;   ///< the other ranks' slot results
    long long exchanges = 0;
    long long rebalances = 0;
    long long grainsMoved = 0;     ///< grains that changed rank between evaluations, summed
    double lastImbalance = 1.0;    ///< max / mean of the ranks' work at the last evaluation
};

class ContactDecomposition
{
public:
    /// @param ranks the group (outlives this); its rank() is this process
    /// @param rebalanceAbove redraw the sub-domains when max / mean of the ranks' work exceeds
    ///        this (and the best split of the last redraw by the same factor), at most every
    ///        50 evaluations
    explicit ContactDecomposition(RankGroup& ranks, double rebalanceAbove = 1.1);

    RankGroup& ranks() { return mRanks; }
    const RankGroup& rankGroup() const { return mRanks; }

    /// Before the slots of @a contacts (current for @a world) are evaluated: which of them
    /// this rank evaluates (nonzero), by the owner of each slot's first grain.
    const std::vector<char>& assign(const World& world, const ContactList& contacts);

    /// After this rank has evaluated its slots: every other slot's result, counts, shear
    /// history and (if @a withForces) point forces, from the rank that evaluated it.
    /// Collective.
    void share(ContactList& contacts, bool withForces);

    /// The rank that owns each grain at the last assign() (by grain index).
    const std::vector<int>& grainOwners() const { return mGrainOwner; }
    const WorkBisection& domains() const { return mDomains; }
    const DecompositionCounters& counters() const { return mCounters; }

private:
    void rebalance(const std::vector<Vec3>& centres);
    /// max / mean of the ranks' work under the current owners (1 when there is none).
    double imbalance() const;

    RankGroup& mRanks;
    double mRebalanceAbove;
    double mRedrawAbove = 0.0;           ///< the imbalance that triggers the next redraw
    WorkBisection mDomains;
    bool mDrawn = false;
    long long mEvaluations = 0, mLastRedraw = 0;
    std::vector<double> mGrainWork;      ///< node checks of each grain's slots, last evaluation
    std::vector<int> mGrainOwner, mPreviousOwner;
    std::vector<int> mSlotOwner;
    std::vector<char> mMine;
    std::vector<char> mSend, mReceived;
    std::vector<size_t> mStarts;
    DecompositionCounters mCounters;
};

} // namespace lsdem
