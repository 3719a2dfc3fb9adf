// GhostDecomposition's collective operations: the all-to-all exchange, the sorted gather of
// ordered sums, and the whole world gathered on every rank.
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

bool keyLess(const OrderedTerm& a, const OrderedTerm& b)
{
    return std::lexicographical_compare(a.key, a.key + 3, b.key, b.key + 3);
}

} // namespace

void GhostDecomposition::exchange(const std::vector<std::vector<char>>& toEach,
                                  std::vector<char>& received, std::vector<size_t>& starts)
{
    const Stopwatch watch;
    mRanks.allToAll(toEach, received, starts);
    mCounters.exchangeSeconds += watch.seconds();
    const int me = mRanks.rank();
    for (int r = 0; r < mRanks.ranks(); ++r) {
        if (r == me) continue;
        mCounters.bytesSent += static_cast<long long>(toEach[size_t(r)].size());
        mCounters.bytesReceived +=
            static_cast<long long>(starts[size_t(r) + 1] - starts[size_t(r)]);
    }
}

std::vector<OrderedTerm> GhostDecomposition::gatherSorted(const std::vector<OrderedTerm>& mine)
{
    std::vector<char> bytes(mine.size() * sizeof(OrderedTerm));
    if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
    std::vector<char> all;
    std::vector<size_t> starts;
    const Stopwatch watch;
    mRanks.allGather(bytes, all, starts);
    mCounters.exchangeSeconds += watch.seconds();
    mCounters.bytesSent += static_cast<long long>(bytes.size());
    mCounters.bytesReceived += static_cast<long long>(all.size() - bytes.size());
    ++mCounters.sumsGathered;
    std::vector<OrderedTerm> terms(all.size() / sizeof(OrderedTerm));
    if (!terms.empty()) std::memcpy(terms.data(), all.data(), terms.size() * sizeof(OrderedTerm));
    std::sort(terms.begin(), terms.end(), keyLess);
    return terms;
}

World GhostDecomposition::gatherWorld(const World& local)
{
    std::vector<char> mine;
    Writer w(mine);
    for (size_t i = 0; i < local.grains.size(); ++i) {
        if (!mOwned[i]) continue;
        w.value(kOwnedGrain);
        w.value(mGlobal[i]);
        grainpacking::putGrain(w, local.grains[i], assetIndex(local, local.grains[i].asset.get()));
    }
    // Every history of the list, empty ones too: a pair's from the owner of its first grain.
    for (const auto& [key, h] : local.pairHistory) {
        if (!mOwned[size_t(key.first)]) continue;
        w.value(kPairHistory);
        w.value(mGlobal[size_t(key.first)]);
        w.value(mGlobal[size_t(key.second)]);
        grainpacking::putHistory(w, h.shearOnFirstNodes);
        grainpacking::putHistory(w, h.shearOnSecondNodes);
    }
    for (const auto& [key, h] : local.boundaryHistory) {
        w.value(kBoundaryHistory);
        w.value(mGlobal[size_t(key.first)]);
        w.value(key.second);
        grainpacking::putHistory(w, h);
    }
    // To rank 0 only: the others send, and hold no more than their part.
    std::vector<std::vector<char>> toEach(size_t(mRanks.ranks()));
    toEach[0].swap(mine);
    std::vector<char> all;
    std::vector<size_t> starts;
    const Stopwatch watch;
    mRanks.allToAll(toEach, all, starts);
    mCounters.exchangeSeconds += watch.seconds();
    if (mRanks.rank() != 0) return World();

    World out = local;
    out.grains.clear();
    out.pairHistory.clear();
    out.boundaryHistory.clear();
    std::vector<std::pair<int, Grain>> grains;
    std::vector<ShearHistory::Entry> buffer;
    Reader in(all.data(), all.data() + all.size());
    while (!in.atEnd()) {
        const char tag = in.value<char>();
        if (tag == kOwnedGrain) {
            const int id = in.value<int>();
            grains.emplace_back(id, grainpacking::getGrain(in, local));
        } else if (tag == kPairHistory) {
            const int a = in.value<int>(), b = in.value<int>();
            PairHistory h;
            grainpacking::getHistory(in, h.shearOnFirstNodes, buffer);
            grainpacking::getHistory(in, h.shearOnSecondNodes, buffer);
            out.pairHistory.emplace(std::make_pair(a, b), std::move(h));
        } else if (tag == kBoundaryHistory) {
            const int a = in.value<int>(), b = in.value<int>();
            ShearHistory h;
            grainpacking::getHistory(in, h, buffer);
            out.boundaryHistory.emplace(std::make_pair(a, b), std::move(h));
        } else {
            throw std::runtime_error("GhostDecomposition: a malformed gathered world");
        }
    }
    std::sort(grains.begin(), grains.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    if (grains.size() != size_t(mGlobalCount))
        throw std::logic_error("GhostDecomposition: the ranks own " +
                               std::to_string(grains.size()) + " grains, not " +
                               std::to_string(mGlobalCount));
    for (size_t g = 0; g < grains.size(); ++g) {
        if (grains[g].first != static_cast<int>(g))
            throw std::logic_error("GhostDecomposition: grain " + std::to_string(g) +
                                   " is owned by no rank or by two");
        out.grains.push_back(std::move(grains[g].second));
    }
    return out;
}

} // namespace lsdem
