#include "lsdem/contact/PlaneContact.h"

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
    auto testNodes = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + pose.position;
            ++stats.nodesSampled;
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
    if (a.nodeBlocks.empty()) {
        testNodes(0, static_cast<int>(count));
        return;
    }
    // A grain touching a wall has most of its node blocks wholly in front of it: skip those.
    for (const NodeBlock& block : a.nodeBlocks) {
        const Vec3 center = rotation * block.center + pose.position;
        if (plane.signedDistance(center) > block.radius) {
            stats.nodesCulled += block.end - block.begin;
            continue;
        }
        testNodes(block.begin, block.end);
    }
}

} // namespace lsdem
