#include "lsdem/mesh/SampleElimination.h"

#include "lsdem/core/Error.h"

#include "PointBins.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace lsdem {

namespace {

/// A max-heap of point indices by weight (ties: the lower index on top) that can lower an
/// entry's weight in place.
class CrowdingHeap
{
public:
    explicit CrowdingHeap(const std::vector<double>& weight) : mWeight(weight)
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
               (mWeight[size_t(a)] == mWeight[size_t(b)] && a < b);
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
    std::vector<int> mHeap, mPosition;
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

    auto distance = [&](size_t i, int j) { return (candidates[size_t(j)] - candidates[i]).norm(); };
    const Vec3 none = candidates.front();  // (the bins widen their box to hold every point)
    // Each point's neighbours within reach, listed once (in parallel: each point's list is
    // its own) in the bins' order: the removals below read them a hundred thousand times,
    // and a list is read faster than the bins are searched again.
    std::vector<uint32_t> firstNeighbour(candidates.size() + 1, 0);
    std::vector<int> neighbours;
    {
        const PointBins bins(candidates, none, none, reach);
        auto forNeighbours = [&](size_t i, auto&& visit) {
            bins.forEachWithin(candidates[i], reach, [&](int j) {
                if (size_t(j) != i && distance(i, j) < reach) visit(j);
            });
        };
        tbb::parallel_for(size_t(0), candidates.size(), [&](size_t i) {
            uint32_t n = 0;
            forNeighbours(i, [&](int) { ++n; });
            firstNeighbour[i + 1] = n;
        });
        uint64_t total = 0;  // (summed wide: 4 bytes each is all the lists can spend)
        for (size_t i = 0; i < candidates.size(); ++i) {
            total += firstNeighbour[i + 1];
            if (total > std::numeric_limits<uint32_t>::max())
                throw Error("", "sample elimination: " + std::to_string(candidates.size()) +
                                    " points have more than 2^32 neighbours in all",
                            "place fewer nodes");
            firstNeighbour[i + 1] = uint32_t(total);
        }
        neighbours.resize(firstNeighbour.back());
        tbb::parallel_for(size_t(0), candidates.size(), [&](size_t i) {
            uint32_t k = firstNeighbour[i];
            forNeighbours(i, [&](int j) { neighbours[k++] = j; });
        });
    }
    // Each point's weight, its neighbours' summed in the list's order.
    std::vector<double> weight(candidates.size(), 0.0);
    tbb::parallel_for(size_t(0), candidates.size(), [&](size_t i) {
        double sum = 0.0;
        for (uint32_t k = firstNeighbour[i]; k < firstNeighbour[i + 1]; ++k)
            sum += weightOf(distance(i, neighbours[k]));
        weight[i] = sum;
    });

    CrowdingHeap heap(weight);
    std::vector<char> removed(candidates.size(), 0);
    for (size_t left = candidates.size(); left > count; --left) {
        const auto worst = size_t(heap.top());
        heap.pop();
        removed[worst] = 1;
        for (uint32_t k = firstNeighbour[worst]; k < firstNeighbour[worst + 1]; ++k) {
            const int j = neighbours[k];
            if (removed[size_t(j)]) continue;
            weight[size_t(j)] -= weightOf(distance(worst, j));
            heap.lowered(j);
        }
    }
    std::vector<int> kept;
    kept.reserve(count);
    for (size_t i = 0; i < candidates.size(); ++i)
        if (!removed[i]) kept.push_back(int(i));
    return kept;
}

} // namespace lsdem
