// GhostDecomposition's moves of grains between ranks (a redraw): what each rank sends of the
// grains it gives away, and the world rebuilt from what it receives.
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

/// A grain as received by its new holder.
struct Incoming
{
    int id = 0;
    bool owned = false;
    int owner = -1;               ///< a ghost's owner
    std::vector<int> ghostRanks;  ///< an owned grain's ranks that hold it as a ghost
    Grain grain;
    double work = 1.0;
};

struct IncomingPair
{
    int first = 0, second = 0;
    PairHistory history;
};

struct IncomingBoundary
{
    int grain = 0, boundary = 0;
    ShearHistory history;
};

} // namespace

struct GhostDecomposition::Inbox
{
    std::vector<Incoming> grains;
    std::vector<IncomingPair> pairs;
    std::vector<IncomingBoundary> boundaries;
};

void GhostDecomposition::redistribute(World& world)
{
    maybeRebalance(world);
    const Stopwatch packing;
    std::vector<int> newOwner;
    std::vector<std::vector<int>> ghostRanks;
    route(world, newOwner, ghostRanks);
    packMoves(world, newOwner, ghostRanks);
    double packSeconds = packing.seconds();

    exchange(mToEach, mReceived, mStarts);

    const Stopwatch unpacking;
    Inbox inbox;
    unpackMoves(world, inbox);
    rebuildWorld(world, inbox);
    packSeconds += unpacking.seconds();
    mCounters.packSeconds += packSeconds;
    ++mCounters.redistributions;
}

void GhostDecomposition::packMoves(const World& world, const std::vector<int>& newOwner,
                                   const std::vector<std::vector<int>>& ghostRanks)
{
    const int ranks = mRanks.ranks(), me = mRanks.rank();
    // Each owned grain to its new owner (with the ranks that will hold it as a ghost) and to
    // those ranks (with its owner); the histories of its contacts wherever the grain goes
    // (a pair's from the owner of its first grain, which holds them all).
    mToEach.assign(size_t(ranks), {});
    std::vector<Writer> to;
    to.reserve(size_t(ranks));
    for (int r = 0; r < ranks; ++r) to.emplace_back(mToEach[size_t(r)]);
    for (size_t i = 0; i < world.grains.size(); ++i) {
        if (!mOwned[i]) continue;
        const Grain& g = world.grains[i];
        const int asset = assetIndex(world, g.asset.get());
        mCounters.grainsEmigrated += newOwner[i] != me;
        Writer& owner = to[size_t(newOwner[i])];
        owner.value(kOwnedGrain);
        owner.value(mGlobal[i]);
        owner.value(static_cast<int>(ghostRanks[i].size()));
        for (int r : ghostRanks[i]) owner.value(r);
        grainpacking::putGrain(owner, g, asset);
        owner.value(mWork[i]);
        for (int r : ghostRanks[i]) {
            Writer& w = to[size_t(r)];
            w.value(kGhostGrain);
            w.value(mGlobal[i]);
            w.value(newOwner[i]);
            grainpacking::putGrain(w, g, asset);
            w.value(mWork[i]);
        }
    }
    for (const auto& pairAndHistory : world.pairHistory) {
        // Not a structured binding: a lambda may not capture one before C++20 (clang refuses).
        const size_t a = size_t(pairAndHistory.first.first);
        const size_t b = size_t(pairAndHistory.first.second);
        const PairHistory& h = pairAndHistory.second;
        if (!mOwned[a] || h.empty()) continue;  // an empty history is the list's bookkeeping
        const auto send = [&](int r) {
            Writer& w = to[size_t(r)];
            w.value(kPairHistory);
            w.value(mGlobal[a]);
            w.value(mGlobal[b]);
            grainpacking::putHistory(w, h.shearOnFirstNodes);
            grainpacking::putHistory(w, h.shearOnSecondNodes);
        };
        send(newOwner[a]);
        for (int r : ghostRanks[a]) send(r);
    }
    for (const auto& [key, h] : world.boundaryHistory) {
        const size_t a = size_t(key.first);
        if (!mOwned[a] || h.empty()) continue;
        Writer& w = to[size_t(newOwner[a])];
        w.value(kBoundaryHistory);
        w.value(mGlobal[a]);
        w.value(key.second);
        grainpacking::putHistory(w, h);
    }
}

void GhostDecomposition::unpackMoves(const World& world, Inbox& inbox)
{
    const int ranks = mRanks.ranks(), me = mRanks.rank();
    std::vector<ShearHistory::Entry> buffer;
    for (int r = 0; r < ranks; ++r) {
        Reader in(mReceived.data() + mStarts[size_t(r)], mReceived.data() + mStarts[size_t(r) + 1]);
        while (!in.atEnd()) {
            const char tag = in.value<char>();
            if (tag == kOwnedGrain || tag == kGhostGrain) {
                Incoming& g = inbox.grains.emplace_back();
                g.id = in.value<int>();
                g.owned = tag == kOwnedGrain;
                if (g.owned) {
                    g.ghostRanks.resize(size_t(in.value<int>()));
                    for (int& k : g.ghostRanks) k = in.value<int>();
                    mCounters.grainsMigrated += r != me;
                } else {
                    g.owner = in.value<int>();
                }
                g.grain = grainpacking::getGrain(in, world);
                g.work = in.value<double>();
            } else if (tag == kPairHistory) {
                IncomingPair& p = inbox.pairs.emplace_back();
                p.first = in.value<int>();
                p.second = in.value<int>();
                grainpacking::getHistory(in, p.history.shearOnFirstNodes, buffer);
                grainpacking::getHistory(in, p.history.shearOnSecondNodes, buffer);
                mCounters.historiesMigrated += r != me;
            } else if (tag == kBoundaryHistory) {
                IncomingBoundary& b = inbox.boundaries.emplace_back();
                b.grain = in.value<int>();
                b.boundary = in.value<int>();
                grainpacking::getHistory(in, b.history, buffer);
                mCounters.historiesMigrated += r != me;
            } else {
                throw std::runtime_error("GhostDecomposition: a malformed exchange from rank " +
                                         std::to_string(r));
            }
        }
    }
}

void GhostDecomposition::rebuildWorld(World& world, Inbox& inbox)
{
    // This rank's world anew, in global order: its contact list is then the one-process
    // list's part, in the same order.
    std::vector<Incoming>& grains = inbox.grains;
    std::sort(grains.begin(), grains.end(),
              [](const Incoming& a, const Incoming& b) { return a.id < b.id; });
    const int ranks = mRanks.ranks();
    const std::vector<int> previous = mGlobal;
    const size_t n = grains.size();
    world.grains.clear();
    world.grains.reserve(n);
    mGlobal.resize(n);
    mOwned.resize(n);
    mWork.resize(n);
    mSendGhosts.assign(size_t(ranks), {});
    mReceiveGhosts.assign(size_t(ranks), {});
    int owned = 0;
    for (size_t i = 0; i < n; ++i) {
        Incoming& g = grains[i];
        if (i > 0 && grains[i - 1].id == g.id)
            throw std::logic_error("GhostDecomposition: grain " + std::to_string(g.id) +
                                   " received twice");
        world.grains.push_back(std::move(g.grain));
        mGlobal[i] = g.id;
        mOwned[i] = g.owned;
        mWork[i] = g.work;
        owned += g.owned;
        // Both lists in global order, so a ghost update needs no indices.
        if (g.owned)
            for (int r : g.ghostRanks) mSendGhosts[size_t(r)].push_back(static_cast<int>(i));
        else
            mReceiveGhosts[size_t(g.owner)].push_back(static_cast<int>(i));
    }
    mRenumbering.resize(previous.size());
    for (size_t i = 0; i < previous.size(); ++i) mRenumbering[i] = localOf(previous[i]);
    world.pairHistory.clear();
    for (IncomingPair& p : inbox.pairs) {
        const int a = localOf(p.first), b = localOf(p.second);
        if (a < 0 || b < 0 || (!mOwned[size_t(a)] && !mOwned[size_t(b)])) continue;
        world.pairHistory.emplace(std::make_pair(a, b), std::move(p.history));
    }
    world.boundaryHistory.clear();
    for (IncomingBoundary& b : inbox.boundaries) {
        const int a = localOf(b.grain);
        if (a < 0 || !mOwned[size_t(a)]) continue;
        world.boundaryHistory.emplace(std::make_pair(a, b.boundary), std::move(b.history));
    }
    mCounters.owned = owned;
    mCounters.ghosts = static_cast<int>(n) - owned;
}

} // namespace lsdem
