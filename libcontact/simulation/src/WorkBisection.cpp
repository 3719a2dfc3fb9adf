#include "lsdem/simulation/WorkBisection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lsdem {

WorkBisection WorkBisection::balance(const std::vector<Vec3>& points,
                                     const std::vector<double>& weights, int parts)
{
    if (parts < 1) throw std::invalid_argument("WorkBisection: parts must be >= 1");
    if (weights.size() != points.size())
        throw std::invalid_argument("WorkBisection: one weight per point");
    WorkBisection b;
    b.mParts = parts;
    b.mNodes.clear();
    std::vector<int> indices(points.size());
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<int>(i);
    b.cut(points, weights, indices, 0, indices.size(), 0, parts);
    return b;
}

int WorkBisection::cut(const std::vector<Vec3>& points, const std::vector<double>& weights,
                       std::vector<int>& indices, size_t begin, size_t end, int firstPart,
                       int parts)
{
    const int self = static_cast<int>(mNodes.size());
    mNodes.push_back(Node{});
    if (parts == 1) {
        mNodes[size_t(self)].part = firstPart;
        return self;
    }
    const int partsBelow = parts / 2;

    // Across the longest side of the points' box (the first such axis on a tie).
    int axis = 0;
    if (begin < end) {
        Vec3 lo = points[size_t(indices[begin])], hi = lo;
        for (size_t k = begin; k < end; ++k) {
            lo = lo.cwiseMin(points[size_t(indices[k])]);
            hi = hi.cwiseMax(points[size_t(indices[k])]);
        }
        (hi - lo).maxCoeff(&axis);
    }
    auto less = [&](int a, int b) {
        const double xa = points[size_t(a)][axis], xb = points[size_t(b)][axis];
        return xa < xb || (xa == xb && a < b);
    };
    std::sort(indices.begin() + std::ptrdiff_t(begin), indices.begin() + std::ptrdiff_t(end),
              less);

    // The split whose lower side's work is closest to its share; a plane can only pass
    // between points of different coordinates, so equal ones stay together.
    double total = 0.0;
    for (size_t k = begin; k < end; ++k) total += weights[size_t(indices[k])];
    const double target = total * partsBelow / parts;
    size_t split = begin;
    double bestMiss = std::numeric_limits<double>::infinity(), below = 0.0;
    for (size_t m = begin; m <= end; ++m) {
        const bool separable =
            m == begin || m == end ||
            points[size_t(indices[m - 1])][axis] < points[size_t(indices[m])][axis];
        if (separable && std::abs(below - target) < bestMiss) {
            bestMiss = std::abs(below - target);
            split = m;
        }
        if (m < end) below += weights[size_t(indices[m])];
    }
    // Points with x[axis] >= at go above.
    double at = 0.0;
    if (begin == end) {
        at = 0.0;
    } else if (split == end) {
        at = std::nextafter(points[size_t(indices[end - 1])][axis],
                            std::numeric_limits<double>::infinity());
    } else if (split == begin) {
        at = points[size_t(indices[begin])][axis];
    } else {
        const double a = points[size_t(indices[split - 1])][axis];
        const double b = points[size_t(indices[split])][axis];
        const double middle = 0.5 * (a + b);
        at = middle > a ? middle : b;
    }
    const int belowNode = cut(points, weights, indices, begin, split, firstPart, partsBelow);
    const int aboveNode =
        cut(points, weights, indices, split, end, firstPart + partsBelow, parts - partsBelow);
    Node& node = mNodes[size_t(self)];
    node.part = -1;
    node.axis = axis;
    node.at = at;
    node.below = belowNode;
    node.above = aboveNode;
    return self;
}

int WorkBisection::partOf(const Vec3& point) const
{
    const Node* node = &mNodes[0];
    while (node->part < 0)
        node = &mNodes[size_t(point[node->axis] >= node->at ? node->above : node->below)];
    return node->part;
}

void WorkBisection::partsNear(const Vec3& point, double reach, std::vector<int>& out) const
{
    out.clear();
    collectNear(0, point, reach, out);
    std::sort(out.begin(), out.end());
}

void WorkBisection::collectNear(int node, const Vec3& point, double reach,
                                std::vector<int>& out) const
{
    const Node& n = mNodes[size_t(node)];
    if (n.part >= 0) {
        out.push_back(n.part);
        return;
    }
    // The same test partOf makes, for the cube's two ends along the cut's axis.
    if (point[n.axis] - reach < n.at) collectNear(n.below, point, reach, out);
    if (point[n.axis] + reach >= n.at) collectNear(n.above, point, reach, out);
}

} // namespace lsdem
