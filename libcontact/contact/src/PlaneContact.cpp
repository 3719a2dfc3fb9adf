#include "lsdem/contact/PlaneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"

#include <cmath>

namespace lsdem {

void findPlaneContacts(const GrainAsset& a, const RigidPose& pose, const Plane& plane,
                       std::vector<NodeContact>& out, NodeCheckStats& stats)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    if (plane.signedDistance(pose.position) > a.boundingRadius) {  // the whole grain is clear
        stats.nodesCulled += count;
        return;
    }
    const Eigen::Matrix3d rotation = pose.orientation.toRotationMatrix();
    // The plane in the grain's frame: a node's distance there costs a dot product and no
    // rotation. With a hair of slack for round-off it only rules nodes out; the distance that
    // decides (and makes the depth) is the world one, as before.
    const Vec3 normalInGrain = rotation.transpose() * plane.normal;
    const double offset = plane.signedDistance(pose.position);
    const double slack = 1e-9 * (a.boundingRadius + std::abs(offset));
    const Vec3* positions = a.nodes.positions.data();
    auto visit = [&](int begin, int end) {
        // Most nodes of a block near the wall are in front of it: that test runs on locals
        // (registers), and the count is added once.
        const Vec3 n = normalInGrain;
        const double front = slack - offset;
        stats.nodesSampled += end - begin;
        for (int i = begin; i < end; ++i) {
            if (positions[i].dot(n) > front) continue;  // in front
            const Vec3 x = rotation * positions[i] + pose.position;
            const double distance = plane.signedDistance(x);
            if (!(distance < 0.0) || !plane.withinPatch(x, distance)) continue;
            ++stats.nodesInContact;
            NodeContact c;
            c.node = i;
            c.depth = -distance;
            c.normal = plane.normal;
            c.point = x + 0.5 * c.depth * plane.normal;
            c.area = a.nodes.areas[i];
            out.push_back(c);
        }
    };
    // A grain touching a wall has most of its nodes wholly in front of it: skip those.
    auto isClear = [&](const NodeBlock& run) {
        return run.center.dot(normalInGrain) + offset > run.radius + slack;
    };
    forEachBlockNotClear(a, isClear, visit, stats);
}

} // namespace lsdem
