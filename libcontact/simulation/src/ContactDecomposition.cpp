#include "lsdem/simulation/ContactDecomposition.h"

#include "SlotResults.h"

#include "lsdem/ls/Stopwatch.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lsdem {

namespace {

/// Evaluations between two redraws at least: the work of a grain's contacts moves with every
/// collision, and a redraw hands grains to ranks whose cached node blocks (CandidateBlocks.h)
/// are cold, which costs work of its own.
constexpr long long kEvaluationsBetweenRedraws = 50;

} // namespace

ContactDecomposition::ContactDecomposition(RankGroup& ranks, double rebalanceAbove)
    : mRanks(ranks), mRebalanceAbove(rebalanceAbove)
{
    if (!(rebalanceAbove >= 1.0))
        throw std::invalid_argument("ContactDecomposition: rebalanceAbove must be >= 1");
}

double ContactDecomposition::imbalance() const
{
    std::vector<double> work(size_t(mRanks.ranks()), 0.0);
    double total = 0.0;
    for (size_t g = 0; g < mGrainOwner.size(); ++g) {
        work[size_t(mGrainOwner[g])] += mGrainWork[g];
        total += mGrainWork[g];
    }
    if (!(total > 0.0)) return 1.0;
    return *std::max_element(work.begin(), work.end()) / (total / double(work.size()));
}

void ContactDecomposition::rebalance(const std::vector<Vec3>& centres)
{
    // A grain whose state is no longer finite is about to stop the run (Simulation's check);
    // until then it must not upset the sort of the bisection.
    std::vector<Vec3> points = centres;
    for (Vec3& p : points)
        if (!p.allFinite()) p = Vec3::Zero();
    mDomains = WorkBisection::balance(points, mGrainWork, mRanks.ranks());
    mDrawn = true;
    mLastRedraw = mEvaluations;
    ++mCounters.rebalances;
    for (size_t g = 0; g < points.size(); ++g) mGrainOwner[g] = mDomains.partOf(centres[g]);
    // The best this split does with the work it was drawn for: work that cannot be split
    // finer (few grains, one heavy grain) must not redraw it at every evaluation.
    mRedrawAbove = std::max(mRebalanceAbove, mRebalanceAbove * imbalance());
}

const std::vector<char>& ContactDecomposition::assign(const World& world,
                                                      const ContactList& contacts)
{
    const size_t n = world.grains.size();
    std::vector<Vec3> centres(n);
    for (size_t g = 0; g < n; ++g) centres[g] = world.grains[g].body.pose.position;
    if (mGrainWork.size() != n) {  // a new world, or grains added or removed: start over
        mGrainWork.assign(n, 1.0);
        mDrawn = false;
    }
    mPreviousOwner.swap(mGrainOwner);
    mGrainOwner.resize(n);
    if (!mDrawn) {
        rebalance(centres);
        // Drawn by grain count (no work measured yet): the next evaluation may redraw.
        mLastRedraw = mEvaluations - kEvaluationsBetweenRedraws;
    } else {
        tbb::parallel_for(size_t(0), n,
                          [&](size_t g) { mGrainOwner[g] = mDomains.partOf(centres[g]); });
        if (mEvaluations - mLastRedraw >= kEvaluationsBetweenRedraws &&
            imbalance() > mRedrawAbove)
            rebalance(centres);
    }
    ++mEvaluations;
    mCounters.lastImbalance = imbalance();
    if (mPreviousOwner.size() == n)
        for (size_t g = 0; g < n; ++g) mCounters.grainsMoved += mGrainOwner[g] != mPreviousOwner[g];

    const std::vector<ContactSlot>& slots = contacts.slots();
    const int me = mRanks.rank();
    mSlotOwner.resize(slots.size());
    mMine.resize(slots.size());
    for (size_t k = 0; k < slots.size(); ++k) {
        mSlotOwner[k] = mGrainOwner[size_t(slots[k].first)];
        mMine[k] = mSlotOwner[k] == me;
    }
    return mMine;
}

void ContactDecomposition::share(ContactList& contacts, bool withForces)
{
    std::vector<ContactSlot>& slots = contacts.slots();
    if (mSlotOwner.size() != slots.size())
        throw std::logic_error("ContactDecomposition::share without assign for this list");
    const Stopwatch packing;
    mSend.clear();
    for (size_t k = 0; k < slots.size(); ++k)
        if (mMine[k]) slotresults::pack(slots[k], withForces, mSend);
    double packSeconds = packing.seconds();

    const Stopwatch exchange;
    mRanks.allGather(mSend, mReceived, mStarts);
    mCounters.exchangeSeconds += exchange.seconds();

    // Each other rank's slots in list order, the ranks in parallel (they fill distinct slots).
    const Stopwatch unpacking;
    const int me = mRanks.rank();
    tbb::parallel_for(0, mRanks.ranks(), [&](int r) {
        if (r == me) return;
        const char* at = mReceived.data() + mStarts[size_t(r)];
        const char* end = mReceived.data() + mStarts[size_t(r) + 1];
        std::vector<ShearHistory::Entry> buffer;
        for (size_t k = 0; k < slots.size(); ++k)
            if (mSlotOwner[k] == r) slotresults::unpack(at, end, withForces, slots[k], buffer);
        if (at != end)
            throw std::runtime_error("ContactDecomposition: rank " + std::to_string(r) +
                                     " sent more slot results than it owns");
    });

    // The work of each grain's slots, for the next balance.
    std::fill(mGrainWork.begin(), mGrainWork.end(), 1.0);
    for (const ContactSlot& s : slots)
        mGrainWork[size_t(s.first)] +=
            double(s.stats.nodesConsidered) + double(s.stats.nodesSampled);
    packSeconds += unpacking.seconds();

    mCounters.packSeconds += packSeconds;
    mCounters.bytesSent += static_cast<long long>(mSend.size());
    mCounters.bytesReceived += static_cast<long long>(mReceived.size() - mSend.size());
    ++mCounters.exchanges;
}

} // namespace lsdem
