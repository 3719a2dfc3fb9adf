#include "lsdem/contact/PlaneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"

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
    auto visit = [&](int i) {
        const Vec3 x = rotation * a.nodes.positions[i] + pose.position;
        ++stats.nodesSampled;
        const double distance = plane.signedDistance(x);
        if (!(distance < 0.0) || !plane.withinPatch(x, distance)) return;
        ++stats.nodesInContact;
        NodeContact c;
        c.node = i;
        c.depth = -distance;
        c.normal = plane.normal;
        c.point = x + 0.5 * c.depth * plane.normal;
        c.area = a.nodes.areas[i];
        out.push_back(c);
    };
    // A grain touching a wall has most of its nodes wholly in front of it: skip those.
    auto isClear = [&](const NodeBlock& run) {
        return plane.signedDistance(rotation * run.center + pose.position) > run.radius;
    };
    forEachNodeNotClear(a, isClear, visit, stats);
}

} // namespace lsdem
