#include "lsdem/contact/PlaneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/contact/PatchQuadrature.h"

#include <cmath>
#include <stdexcept>

namespace lsdem {

namespace {

/// The patch of node @a i of @a a (at @a rotation, world position @a x, @a distance in front
/// of @a plane) against the plane: appended to @a out if any of it is behind.
void addPlanePatchContact(const GrainAsset& a, int i, const Eigen::Matrix3d& rotation,
                          const Vec3& x, double distance, const Plane& plane,
                          std::vector<NodeContact>& out, NodeCheckStats& stats)
{
    const NodeShape& shape = a.nodeShapes[static_cast<size_t>(i)];
    if (distance >= double(shape.reach) + double(shape.lift)) return;  // out of its reach
    const PatchFrame frame = patchFrame(shape, rotation);
    // The plane's φ is the distance in front of it, ∇φ its normal, and it does not bend.
    const PatchDepth depth = patchDepth(frame, distance, plane.normal, 0.0, 0.0, 0.0);
    addPatchContact(i, shape, frame, depth, x, plane.normal, out, stats.nodesInContact);
}

} // namespace

void findPlaneContacts(const GrainAsset& a, const RigidPose& pose, const Plane& plane,
                       std::vector<NodeContact>& out, NodeCheckStats& stats, bool patches)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    if (patches && a.nodeShapes.size() != a.nodes.size())
        throw std::logic_error("findPlaneContacts: patch quadrature on an asset without node shapes");
    // How far in front of the plane a node may be and still have its patch reach behind it.
    const double reach = patches ? a.patchReach : 0.0;
    if (plane.signedDistance(pose.position) > a.boundingRadius + reach) {  // the whole grain is clear
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
        const double front = slack + reach - offset;
        stats.nodesSampled += end - begin;
        for (int i = begin; i < end; ++i) {
            if (positions[i].dot(n) > front) continue;  // in front
            const Vec3 x = rotation * positions[i] + pose.position;
            const double distance = plane.signedDistance(x);
            if (patches) {
                if (distance < reach && plane.withinPatch(x, distance))
                    addPlanePatchContact(a, i, rotation, x, distance, plane, out, stats);
                continue;
            }
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
        return run.center.dot(normalInGrain) + offset > run.radius + slack + reach;
    };
    forEachBlockNotClear(a, isClear, visit, stats);
}

} // namespace lsdem
