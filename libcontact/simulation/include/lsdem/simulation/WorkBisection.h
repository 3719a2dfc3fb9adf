/// @file WorkBisection.h
/// @brief Space cut into parts of about equal work by recursive coordinate bisection: the
///        points (grain centres), each with its work, are split across the longest side of
///        their bounding box where the work on either side is in proportion to the parts each
///        side gets, and each side again, until each part is one rank's sub-domain.
///
/// The cuts are planes, so any point of space (a grain that has moved since) belongs to
/// exactly one part. Deterministic: the same points and weights give the same cuts on every
/// process (no threads, ties broken by point index).
#pragma once

#include "lsdem/core/Vec3.h"

#include <vector>

namespace lsdem {

class WorkBisection
{
public:
    /// One part: all of space.
    WorkBisection() = default;

    /// Cut space into @a parts (>= 1) parts of about equal total @a weights (>= 0, one per
    /// point of @a points). A part may hold no point (more parts than points).
    static WorkBisection balance(const std::vector<Vec3>& points,
                                 const std::vector<double>& weights, int parts);

    int parts() const { return mParts; }
    /// The part that holds @a point.
    int partOf(const Vec3& point) const;
    /// Every part with a point within @a reach of @a point along each axis (a cube around it:
    /// every part within that distance, and maybe a few just beyond), ascending, into @a out.
    void partsNear(const Vec3& point, double reach, std::vector<int>& out) const;

private:
    /// A node of the cut tree: a leaf (part >= 0), or a plane x[axis] = at whose lower side
    /// is node `below` and whose upper side (x[axis] >= at) is node `above`.
    struct Node
    {
        int part = 0;
        int axis = 0;
        double at = 0.0;
        int below = -1, above = -1;
    };

    int cut(const std::vector<Vec3>& points, const std::vector<double>& weights,
            std::vector<int>& indices, size_t begin, size_t end, int firstPart, int parts);

    void collectNear(int node, const Vec3& point, double reach, std::vector<int>& out) const;

    int mParts = 1;
    std::vector<Node> mNodes{Node{}};
};

} // namespace lsdem
