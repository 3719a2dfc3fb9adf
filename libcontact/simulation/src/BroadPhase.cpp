#include "lsdem/simulation/BroadPhase.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <tbb/parallel_for.h>

namespace lsdem {

std::vector<std::pair<int, int>> findCandidatePairs(const std::vector<Vec3>& centers,
                                                    const std::vector<double>& radii,
                                                    double margin)
{
    std::vector<std::pair<int, int>> pairs;
    const int n = static_cast<int>(centers.size());
    if (n < 2) return pairs;
    // Cells as wide as the largest reach, so overlapping spheres sit in neighbouring cells.
    double largest = 0.0;
    Vec3 lo = centers[0];
    for (int i = 0; i < n; ++i) {
        largest = std::max(largest, radii[i]);
        lo = lo.cwiseMin(centers[i]);
    }
    const double cell = std::max(2.0 * largest + margin, 1e-300);
    auto cellOf = [&](const Vec3& c) {
        return Eigen::Vector3i(static_cast<int>(std::floor((c.x() - lo.x()) / cell)),
                               static_cast<int>(std::floor((c.y() - lo.y()) / cell)),
                               static_cast<int>(std::floor((c.z() - lo.z()) / cell)));
    };
    // Cell coordinates start at 0 (lo is the minimum) and neighbours at -1: offset by one and
    // pack 21 bits each.
    auto key = [](const Eigen::Vector3i& c) {
        const auto field = [](int v) { return uint64_t(int64_t(v) + 1) & 0x1FFFFFu; };
        return (field(c.x()) << 42) | (field(c.y()) << 21) | field(c.z());
    };
    std::unordered_map<uint64_t, std::vector<int>> grid;
    grid.reserve(static_cast<size_t>(n));
    std::vector<Eigen::Vector3i> cells(n);
    for (int i = 0; i < n; ++i) {
        cells[i] = cellOf(centers[i]);
        grid[key(cells[i])].push_back(i);
    }
    // Each grain's partners of higher index, found in parallel into its own list; the lists
    // are then joined in grain order, so the result is sorted and thread-count independent.
    std::vector<std::vector<int>> partners(static_cast<size_t>(n));
    tbb::parallel_for(0, n, [&](int i) {
        std::vector<int>& mine = partners[static_cast<size_t>(i)];
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(key(cells[i] + Eigen::Vector3i(dx, dy, dz)));
                    if (it == grid.end()) continue;
                    for (int j : it->second) {
                        if (j <= i) continue;
                        const double reach = radii[i] + radii[j] + margin;
                        if ((centers[i] - centers[j]).squaredNorm() <= reach * reach)
                            mine.push_back(j);
                    }
                }
        std::sort(mine.begin(), mine.end());
        // Keys wrap beyond 2²¹ cells per axis; a wrapped key can only repeat a pair, never
        // lose one.
        mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    });
    size_t total = 0;
    for (const std::vector<int>& mine : partners) total += mine.size();
    pairs.reserve(total);
    for (int i = 0; i < n; ++i)
        for (int j : partners[static_cast<size_t>(i)]) pairs.emplace_back(i, j);
    return pairs;
}

} // namespace lsdem
