#include "studies/RunSchedule.h"

#include <algorithm>
#include <functional>
#include <numeric>
#include <queue>

namespace lsdem {

std::vector<size_t> largestFirst(const std::vector<double>& costs)
{
    std::vector<size_t> order(costs.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return costs[a] > costs[b]; });
    return order;
}

double largestFirstMakespan(const std::vector<double>& costs, int ranks)
{
    // Each rank's finishing time so far; the next run goes to the one that is free first.
    std::priority_queue<double, std::vector<double>, std::greater<double>> freeAt;
    for (int r = 0; r < std::max(ranks, 1); ++r) freeAt.push(0.0);
    double end = 0.0;
    for (size_t i : largestFirst(costs)) {
        const double done = freeAt.top() + costs[i];
        freeAt.pop();
        freeAt.push(done);
        end = std::max(end, done);
    }
    return end;
}

std::string RunShares::text() const
{
    int total = 0;
    std::string each;
    for (int n : mRuns) {
        total += n;
        each += " " + std::to_string(n);
    }
    return std::to_string(total) + " runs over " + std::to_string(mRuns.size()) +
           " ranks (runs per rank:" + each + ")";
}

} // namespace lsdem
