#include "lsdem/simulation/BroadPhase.h"

#include "lsdem/core/OrderedCollect.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lsdem {

namespace {

/// Cells per axis at most: keys pack three cell coordinates (each offset by one, so a
/// neighbour at -1 is still >= 0) into 21 bits each without wrapping.
constexpr double kMaxCellsPerAxis = double(1 << 20);

uint64_t cellKey(int64_t x, int64_t y, int64_t z)
{
    return (uint64_t(x + 1) << 42) | (uint64_t(y + 1) << 21) | uint64_t(z + 1);
}

/// A grain in the sorted cell list.
struct CellEntry
{
    uint64_t key;
    int grain;
    bool operator<(const CellEntry& o) const
    {
        return key < o.key || (key == o.key && grain < o.grain);
    }
};

} // namespace

std::vector<std::pair<int, int>> findCandidatePairs(const std::vector<Vec3>& centers,
                                                    const std::vector<double>& radii,
                                                    double margin)
{
    const int n = static_cast<int>(centers.size());
    if (n < 2) return {};
    // Cells as wide as the largest reach, so overlapping spheres sit in neighbouring cells;
    // wider if the grains spread over more than 2²⁰ of them (a grain flung far away): pairs
    // are still decided by their distance, only more of them are looked at.
    double largest = 0.0;
    Vec3 lo = centers[0], hi = centers[0];
    for (int i = 0; i < n; ++i) {
        largest = std::max(largest, radii[size_t(i)]);
        lo = lo.cwiseMin(centers[size_t(i)]);
        hi = hi.cwiseMax(centers[size_t(i)]);
    }
    double cell = std::max(2.0 * largest + margin, 1e-300);
    cell = std::max(cell, (hi - lo).maxCoeff() / kMaxCellsPerAxis);
    std::vector<Eigen::Matrix<int64_t, 3, 1>> cells(static_cast<size_t>(n));
    std::vector<CellEntry> sorted(static_cast<size_t>(n));
    tbb::parallel_for(0, n, [&](int i) {
        const Vec3 c = ((centers[size_t(i)] - lo) / cell).array().floor();
        auto& mine = cells[size_t(i)];
        mine = c.cast<int64_t>().cwiseMin(int64_t(kMaxCellsPerAxis));
        sorted[size_t(i)] = {cellKey(mine.x(), mine.y(), mine.z()), i};
    });
    // Grains sorted by cell (x, then y, then z): the three cells of a column along z are one
    // run of keys. The entries are distinct, so the order is the same on any thread count.
    tbb::parallel_sort(sorted.begin(), sorted.end());

    // Each chunk of grains finds its grains' partners of higher index into its own list; the
    // chunks are joined in order, so the result is sorted and thread-count independent.
    using Pair = std::pair<int, int>;
    auto partnersAbove = [&](size_t begin, size_t end, std::vector<Pair>& out) {
        std::vector<int> partners;
        for (int i = int(begin); i < int(end); ++i) {
            partners.clear();
            const auto& c = cells[size_t(i)];
            for (int64_t dx = -1; dx <= 1; ++dx)
                for (int64_t dy = -1; dy <= 1; ++dy) {
                    const uint64_t first = cellKey(c.x() + dx, c.y() + dy, c.z() - 1);
                    const uint64_t last = cellKey(c.x() + dx, c.y() + dy, c.z() + 1);
                    auto it = std::lower_bound(sorted.begin(), sorted.end(),
                                               CellEntry{first, -1});
                    for (; it != sorted.end() && it->key <= last; ++it) {
                        const int j = it->grain;
                        if (j <= i) continue;
                        const double reach = radii[size_t(i)] + radii[size_t(j)] + margin;
                        if ((centers[size_t(i)] - centers[size_t(j)]).squaredNorm() <=
                            reach * reach)
                            partners.push_back(j);
                    }
                }
            std::sort(partners.begin(), partners.end());
            for (int j : partners) out.emplace_back(i, j);
        }
    };
    return collectInOrder<Pair>(size_t(n), 512, partnersAbove);
}

} // namespace lsdem
