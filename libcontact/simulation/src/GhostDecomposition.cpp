#include "lsdem/simulation/GhostDecomposition.h"

#include "GhostRecords.h"

#include "GrainPacking.h"

#include "lsdem/core/Stopwatch.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace lsdem {

namespace {

using grainpacking::Reader;
using grainpacking::Writer;
using namespace ghostrecords;

/// Evaluations between two redraws at least: a redraw moves grains (and their histories) and
/// hands them to ranks whose cached node blocks (CandidateBlocks.h) are cold.
constexpr long long kEvaluationsBetweenRedraws = 50;

/// A point of the bisection: a grain whose state is no longer finite is about to stop the run
/// (Simulation's check); until then it must not upset the sort of the bisection.
Vec3 finiteOrOrigin(const Vec3& p)
{
    return p.allFinite() ? p : Vec3::Zero();
}

} // namespace

GhostDecomposition::GhostDecomposition(RankGroup& ranks, double rebalanceAbove)
    : mRanks(ranks), mRebalanceAbove(rebalanceAbove)
{
    if (!(rebalanceAbove >= 1.0))
        throw std::invalid_argument("GhostDecomposition: rebalanceAbove must be >= 1");
}

int GhostDecomposition::assetIndex(const World&, const GrainAsset* asset) const
{
    const auto it = mAssetIndex.find(asset);
    if (it == mAssetIndex.end())
        throw std::logic_error("GhostDecomposition: a grain's asset is not one of the world's");
    return it->second;
}

int GhostDecomposition::localOf(int id) const
{
    const auto it = std::lower_bound(mGlobal.begin(), mGlobal.end(), id);
    return it != mGlobal.end() && *it == id ? static_cast<int>(it - mGlobal.begin()) : -1;
}

void GhostDecomposition::distribute(World& world, double skin)
{
    const size_t n = world.grains.size();
    mGlobalCount = static_cast<int>(n);
    mAssetIndex.clear();
    for (size_t k = 0; k < world.assets.size(); ++k)
        mAssetIndex[world.assets[k].get()] = static_cast<int>(k);
    double largest = 0.0;
    for (const Grain& g : world.grains) largest = std::max(largest, g.asset->boundingRadius);
    mReach = largest + skin;

    // Every rank holds the same whole world: each draws the same cuts by grain count and
    // takes the part it owns; the first redistribution then sends each grain where it goes.
    std::vector<Vec3> centres(n);
    for (size_t g = 0; g < n; ++g) centres[g] = finiteOrOrigin(world.grains[g].body.pose.position);
    mDomains = WorkBisection::balance(centres, std::vector<double>(n, 1.0), mRanks.ranks());
    ++mCounters.rebalances;
    mEvaluations = 0;
    mLastRedraw = -kEvaluationsBetweenRedraws;  // drawn by count: the first rebuild may redraw
    mRedrawAbove = mRebalanceAbove;
    const int me = mRanks.rank();
    mGlobal.resize(n);
    mOwned.resize(n);
    for (size_t g = 0; g < n; ++g) {
        mGlobal[g] = static_cast<int>(g);
        mOwned[g] = mDomains.partOf(world.grains[g].body.pose.position) == me;
    }
    mWork.assign(n, 1.0);
    redistribute(world);
}

void GhostDecomposition::maybeRebalance(const World& world)
{
    const int ranks = mRanks.ranks();
    OrderedTerm mine;
    mine.key[0] = mRanks.rank();
    for (size_t i = 0; i < mOwned.size(); ++i)
        if (mOwned[i]) mine.value[0] += mWork[i];
    const auto imbalanceOf = [](const std::vector<double>& work) {
        double total = 0.0, largest = 0.0;
        for (double w : work) total += w, largest = std::max(largest, w);
        return total > 0.0 ? largest / (total / double(work.size())) : 1.0;
    };
    std::vector<double> work(size_t(ranks), 0.0);
    for (const OrderedTerm& t : gatherSorted({mine})) work[size_t(t.key[0])] = t.value[0];
    mCounters.lastImbalance = imbalanceOf(work);
    if (mEvaluations - mLastRedraw < kEvaluationsBetweenRedraws ||
        !(mCounters.lastImbalance > mRedrawAbove))
        return;

    // Redraw from every grain's centre and work, in global order (every rank draws the same).
    std::vector<OrderedTerm> grains;
    for (size_t i = 0; i < mOwned.size(); ++i) {
        if (!mOwned[i]) continue;
        OrderedTerm t;
        t.key[0] = mGlobal[i];
        const Vec3 c = finiteOrOrigin(world.grains[i].body.pose.position);
        for (int k = 0; k < 3; ++k) t.value[k] = c[k];
        t.value[3] = mWork[i];
        grains.push_back(t);
    }
    const std::vector<OrderedTerm> all = gatherSorted(grains);
    std::vector<Vec3> points(all.size());
    std::vector<double> weights(all.size());
    for (size_t g = 0; g < all.size(); ++g) {
        points[g] = Vec3(all[g].value[0], all[g].value[1], all[g].value[2]);
        weights[g] = all[g].value[3];
    }
    mDomains = WorkBisection::balance(points, weights, ranks);
    mLastRedraw = mEvaluations;
    ++mCounters.rebalances;
    std::fill(work.begin(), work.end(), 0.0);
    for (size_t g = 0; g < points.size(); ++g)
        work[size_t(mDomains.partOf(points[g]))] += weights[g];
    mCounters.lastImbalance = imbalanceOf(work);
    // The best this split does with the work it was drawn for: work that cannot be split
    // finer (few grains, one heavy grain) must not redraw it at every rebuild.
    mRedrawAbove = std::max(mRebalanceAbove, mRebalanceAbove * mCounters.lastImbalance);
}

void GhostDecomposition::route(const World& world, std::vector<int>& newOwner,
                               std::vector<std::vector<int>>& ghostRanks) const
{
    const size_t n = world.grains.size();
    newOwner.assign(n, -1);
    ghostRanks.assign(n, {});
    const PeriodicCell& cell = world.periodic;
    std::vector<int> near;
    for (size_t i = 0; i < n; ++i) {
        if (!mOwned[i]) continue;
        const Grain& g = world.grains[i];
        const Vec3& c = g.body.pose.position;
        const double reach = g.asset->boundingRadius + mReach;
        newOwner[i] = mDomains.partOf(c);
        // Every rank whose sub-domain comes within this grain's reach of any grain there; in
        // a periodic cell, of the grain or of one of its images across the faces near it (a
        // rank's own contact list makes the images of the grains it holds).
        std::vector<int>& ranks = ghostRanks[i];
        std::vector<Vec3> shifts{Vec3::Zero()};
        for (const Vec3& periods : cell.imagePeriodsNear(c, reach))
            shifts.push_back(cell.imageShift(periods));
        for (const Vec3& shift : shifts) {
            mDomains.partsNear(c + shift, reach, near);
            for (int r : near)
                if (r != newOwner[i]) ranks.push_back(r);
        }
        std::sort(ranks.begin(), ranks.end());
        ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
    }
}

bool GhostDecomposition::updateGhosts(World& world, bool rebuildHere)
{
    const Stopwatch packing;
    const int ranks = mRanks.ranks();
    mToEach.resize(size_t(ranks));
    for (int r = 0; r < ranks; ++r) {
        mToEach[size_t(r)].clear();
        Writer w(mToEach[size_t(r)]);
        for (int i : mSendGhosts[size_t(r)]) grainpacking::putState(w, world.grains[size_t(i)]);
        w.value(static_cast<char>(rebuildHere));  // the vote, last
    }
    double packSeconds = packing.seconds();
    exchange(mToEach, mReceived, mStarts);
    const Stopwatch unpacking;
    bool rebuild = false;
    for (int r = 0; r < ranks; ++r) {
        Reader in(mReceived.data() + mStarts[size_t(r)], mReceived.data() + mStarts[size_t(r) + 1]);
        for (int i : mReceiveGhosts[size_t(r)]) grainpacking::getState(in, world.grains[size_t(i)]);
        rebuild |= in.value<char>() != 0;
        if (!in.atEnd())
            throw std::runtime_error("GhostDecomposition: rank " + std::to_string(r) +
                                     " sent more ghost states than expected");
    }
    packSeconds += unpacking.seconds();
    mCounters.packSeconds += packSeconds;
    ++mCounters.ghostUpdates;
    return rebuild;
}

void GhostDecomposition::recordWork(const ContactList& contacts)
{
    ++mEvaluations;
    std::fill(mWork.begin(), mWork.end(), 1.0);
    for (const ContactSlot& s : contacts.slots())
        mWork[size_t(s.first)] += double(s.stats.nodesConsidered) + double(s.stats.nodesSampled);
}

} // namespace lsdem
