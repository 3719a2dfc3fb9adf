#include "lsdem/mesh/SampleElimination.h"

#include "lsdem/core/Error.h"

#include "PointBins.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>

namespace lsdem {

namespace {

/// A max-heap of points by weight (ties: the lower @a order on top) that can lower an
/// entry's weight in place.
class CrowdingHeap
{
public:
    CrowdingHeap(const std::vector<double>& weight, const std::vector<int>& order)
        : mWeight(weight), mOrder(order)
    {
        mHeap.resize(weight.size());
        mPosition.resize(weight.size());
        for (size_t k = 0; k < weight.size(); ++k) mHeap[k] = int(k);
        for (size_t k = 0; k < mHeap.size(); ++k) mPosition[size_t(mHeap[k])] = int(k);
        for (size_t k = mHeap.size() / 2; k-- > 0;) siftDown(k);
    }
    bool empty() const { return mHeap.empty(); }
    int top() const { return mHeap.front(); }
    void pop()
    {
        moveTo(0, mHeap.back());
        mHeap.pop_back();
        if (!mHeap.empty()) siftDown(0);
    }
    /// Point @a i's weight was lowered: move it down to its place.
    void lowered(int i) { siftDown(size_t(mPosition[size_t(i)])); }

private:
    bool above(int a, int b) const
    {
        return mWeight[size_t(a)] > mWeight[size_t(b)] ||
               (mWeight[size_t(a)] == mWeight[size_t(b)] && mOrder[size_t(a)] < mOrder[size_t(b)]);
    }
    void moveTo(size_t slot, int i)
    {
        mHeap[slot] = i;
        mPosition[size_t(i)] = int(slot);
    }
    void siftDown(size_t k)
    {
        const int item = mHeap[k];
        for (;;) {
            size_t child = 2 * k + 1;
            if (child >= mHeap.size()) break;
            if (child + 1 < mHeap.size() && above(mHeap[child + 1], mHeap[child])) ++child;
            if (!above(mHeap[child], item)) break;
            moveTo(k, mHeap[child]);
            k = child;
        }
        moveTo(k, item);
    }

    const std::vector<double>& mWeight;
    const std::vector<int>& mOrder;
    std::vector<int> mHeap, mPosition;
};

/// Each point's neighbours within reach, listed once (in parallel: each point's list is its
/// own) in the bins' order: the removals read them a hundred thousand times, and a list is
/// read faster than the bins are searched again. The points go by their place in the bins
/// (cell by cell, z slowest), so on a grain's surface a neighbour is at most a slice of cells
/// away, a few thousand places: each is kept as its step from the point's place, in 2 bytes
/// where every step fits (as 4-byte indices the lists were the nodes' stage's largest block),
/// else 4.
template <typename Step>
struct NeighbourLists
{
    std::vector<uint32_t> first;  ///< per place, where its list starts (and the end)
    std::vector<Step> steps;      ///< neighbour's place minus the point's

    template <typename Visit>
    void forEach(size_t place, Visit&& visit) const
    {
        for (uint32_t k = first[place]; k < first[place + 1]; ++k)
            visit(size_t(std::ptrdiff_t(place) + steps[k]));
    }
};

} // namespace

std::vector<int> eliminateSamples(const std::vector<Vec3>& candidates, size_t count, double area)
{
    if (count == 0 || count > candidates.size())
        throw Error("", "sample elimination: asked for " + std::to_string(count) + " of " +
                            std::to_string(candidates.size()) + " points");
    if (!(area > 0.0 && std::isfinite(area)))
        throw Error("", "sample elimination: the surface area must be positive");
    // The largest spacing count points can keep on the area (hexagonal packing), and the
    // neighbourhood twice that; closer than rMin every neighbour weighs the same (Yuksel's
    // β = 0.65, γ = 1.5), which keeps points from gathering in pairs.
    const double rMax = std::sqrt(area / (2.0 * std::sqrt(3.0) * double(count)));
    const double reach = 2.0 * rMax;
    const double rMin =
        reach * (1.0 - std::pow(double(count) / double(candidates.size()), 1.5)) * 0.65;
    auto weightOf = [&](double d) {
        const double x = 1.0 - std::max(d, rMin) / reach, x2 = x * x, x4 = x2 * x2;
        return x4 * x4;  // Yuksel's exponent 8
    };

    const Vec3 none = candidates.front();  // (the bins widen their box to hold every point)
    // From here on the points go by their place in the bins: place a is candidate pointAt[a].
    std::vector<int> pointAt;
    std::vector<uint32_t> first(candidates.size() + 1, 0);
    NeighbourLists<int16_t> shortLists;
    NeighbourLists<int32_t> longLists;  // (one of the two is filled)
    bool shortSteps = true;
    {
        const PointBins bins(candidates, none, none, reach);
        pointAt = bins.pointsByCell();
        // Neighbours, counted and then listed: the places b of the candidates within reach of
        // place a, in the bins' order.
        auto forNeighbours = [&](size_t a, auto&& visit) {
            const auto i = size_t(pointAt[a]);
            bins.forEachWithinPlaced(candidates[i], reach, [&](int j, int b) {
                if (size_t(j) != i && (candidates[size_t(j)] - candidates[i]).norm() < reach)
                    visit(b);
            });
        };
        std::vector<char> farStep(candidates.size(), 0);
        tbb::parallel_for(size_t(0), candidates.size(), [&](size_t a) {
            uint32_t n = 0;
            forNeighbours(a, [&](int b) {
                ++n;
                const std::ptrdiff_t step = b - std::ptrdiff_t(a);
                if (step < std::numeric_limits<int16_t>::min() ||
                    step > std::numeric_limits<int16_t>::max())
                    farStep[a] = 1;
            });
            first[a + 1] = n;
        });
        uint64_t total = 0;  // (summed wide: 4 bytes each is all the lists can spend)
        for (size_t a = 0; a < candidates.size(); ++a) {
            total += first[a + 1];
            if (total > std::numeric_limits<uint32_t>::max())
                throw Error("", "sample elimination: " + std::to_string(candidates.size()) +
                                    " points have more than 2^32 neighbours in all",
                            "place fewer nodes");
            first[a + 1] = uint32_t(total);
        }
        auto list = [&](auto& lists) {
            lists.first = std::move(first);
            lists.steps.resize(lists.first.back());
            tbb::parallel_for(size_t(0), candidates.size(), [&](size_t a) {
                uint32_t k = lists.first[a];
                forNeighbours(a, [&](int b) {
                    using Step = typename std::decay_t<decltype(lists.steps)>::value_type;
                    lists.steps[k++] = Step(b - std::ptrdiff_t(a));
                });
            });
        };
        shortSteps = std::find(farStep.begin(), farStep.end(), 1) == farStep.end();
        if (shortSteps)
            list(shortLists);
        else
            list(longLists);
    }

    // Yuksel's elimination: each point's weight, its neighbours' summed in the lists' order;
    // then the most crowded point removed, and its neighbours' weights lowered, until count
    // are left.
    auto distance = [&](size_t a, size_t b) {
        return (candidates[size_t(pointAt[b])] - candidates[size_t(pointAt[a])]).norm();
    };
    std::vector<char> removed(candidates.size(), 0);
    auto eliminate = [&](const auto& lists) {
        std::vector<double> weight(candidates.size(), 0.0);
        tbb::parallel_for(size_t(0), candidates.size(), [&](size_t a) {
            double sum = 0.0;
            lists.forEach(a, [&](size_t b) { sum += weightOf(distance(a, b)); });
            weight[a] = sum;
        });
        CrowdingHeap heap(weight, pointAt);
        for (size_t left = candidates.size(); left > count; --left) {
            const auto worst = size_t(heap.top());
            heap.pop();
            removed[worst] = 1;
            lists.forEach(worst, [&](size_t b) {
                if (removed[b]) return;
                weight[b] -= weightOf(distance(worst, b));
                heap.lowered(int(b));
            });
        }
    };
    if (shortSteps)
        eliminate(shortLists);
    else
        eliminate(longLists);
    std::vector<int> kept;
    kept.reserve(count);
    for (size_t a = 0; a < candidates.size(); ++a)
        if (!removed[a]) kept.push_back(pointAt[a]);
    std::sort(kept.begin(), kept.end());
    return kept;
}

} // namespace lsdem
