#include "lsdem/simulation/Boundary.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/contact/PatchQuadrature.h"

#include <cmath>
#include <stdexcept>

namespace lsdem {

namespace {

Plane movedPlane(const Boundary& b)
{
    Plane p = b.plane;
    p.point += b.displacement;
    return p;
}

RigidPose movedPose(const Boundary& b)
{
    RigidPose p = b.pose;
    p.position += b.displacement;
    return p;
}

/// Node @a i's patch (at @a x, world) against the sphere (centre @a c, radius @a r), appended
/// to @a out if any of it is inside: φ = |x − c| − r, ∇φ the unit offset n, and the sphere's
/// surface bends away from the patch as (I − n nᵀ)/|x − c|.
void addSpherePatchContact(const GrainAsset& a, int i, const Eigen::Matrix3d& rotation,
                           const Vec3& x, const Vec3& c, double r, std::vector<NodeContact>& out,
                           NodeCheckStats& stats)
{
    const Vec3 offset = x - c;
    const double distance = offset.norm();
    if (distance == 0.0) return;
    const Vec3 n = offset / distance;
    const NodeShape& shape = a.nodeShapes[static_cast<size_t>(i)];
    // The sphere is convex: out of the patch's reach beyond its extent and lift.
    if (distance - r >= double(shape.reach) + double(shape.lift)) return;
    const PatchFrame frame = patchFrame(shape, rotation);
    auto hessian = [&](const Vec3& u, const Vec3& v) {
        return (u.dot(v) - u.dot(n) * v.dot(n)) / distance;
    };
    const PatchDepth depth = patchDepth(
        frame, distance - r, n, hessian(frame.tangent1, frame.tangent1),
        hessian(frame.tangent1, frame.tangent2), hessian(frame.tangent2, frame.tangent2));
    addPatchContact(i, shape, frame, depth, x, n, out, stats.nodesInContact);
}

/// Nodes of @a a inside the sphere (centre @a c, radius @a r): depth r - |x - c|. With
/// @a patches, every node whose patch reaches into it, integrated over its patch.
void findSphereContacts(const GrainAsset& a, const RigidPose& pose, const Vec3& c, double r,
                        std::vector<NodeContact>& out, NodeCheckStats& stats, bool patches)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    // Outside the sphere, a node's patch reaches at most this far in (the sphere is convex).
    const double reach = patches ? a.patchReach : 0.0;
    if ((pose.position - c).norm() > a.boundingRadius + r + reach) {
        stats.nodesCulled += count;
        return;
    }
    const Eigen::Matrix3d rotation = pose.orientation.toRotationMatrix();
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + pose.position;
            ++stats.nodesSampled;
            const Vec3 offset = x - c;
            const double distance = offset.norm();
            if (patches) {
                if (distance < r + reach) addSpherePatchContact(a, i, rotation, x, c, r, out, stats);
                continue;
            }
            if (!(distance < r) || distance == 0.0) continue;
            ++stats.nodesInContact;
            NodeContact nc;
            nc.node = i;
            nc.depth = r - distance;
            nc.normal = offset / distance;
            nc.point = x + 0.5 * nc.depth * nc.normal;
            nc.area = a.nodes.areas[i];
            out.push_back(nc);
        }
    };
    // An indenter touches a small patch of the grain: skip the nodes clear of it.
    auto isClear = [&](const NodeBlock& run) {
        const double within = r + run.radius + reach;
        return (rotation * run.center + pose.position - c).squaredNorm() > within * within;
    };
    forEachBlockNotClear(a, isClear, visit, stats);
}

/// Nodes of @a a outside the cylinder (a point @a c of its axis, unit axis @a axis, radius
/// @a r), grains living inside: depth ρ - r (ρ the node's distance from the axis), the normal
/// pointing back towards the axis.
void findCylinderContacts(const GrainAsset& a, const RigidPose& pose, const Vec3& c,
                          const Vec3& axis, double r, std::vector<NodeContact>& out,
                          NodeCheckStats& stats)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    auto radial = [&](const Vec3& x) {
        const Vec3 offset = x - c;
        return Vec3(offset - offset.dot(axis) * axis);
    };
    if (radial(pose.position).norm() + a.boundingRadius < r) {
        stats.nodesCulled += count;
        return;
    }
    const Eigen::Matrix3d rotation = pose.orientation.toRotationMatrix();
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + pose.position;
            ++stats.nodesSampled;
            const Vec3 outward = radial(x);
            const double distance = outward.norm();
            if (!(distance > r)) continue;
            ++stats.nodesInContact;
            NodeContact nc;
            nc.node = i;
            nc.depth = distance - r;
            nc.normal = -outward / distance;
            nc.point = x + 0.5 * nc.depth * nc.normal;
            nc.area = a.nodes.areas[i];
            out.push_back(nc);
        }
    };
    // A grain touches the wall with one side: skip the nodes well inside.
    auto isClear = [&](const NodeBlock& run) {
        return radial(rotation * run.center + pose.position).norm() + run.radius < r;
    };
    forEachBlockNotClear(a, isClear, visit, stats);
}

/// Nodes of @a a inside an orifice plate: the slab |h| ≤ t/2 (h = (x − c)·axis, @a c the
/// hole's centre in the plate's mid-plane) outside the hole, radius @a r about the axis. The
/// plate in (ρ, h), ρ the distance from the axis, is the half-strip ρ ≥ r, |h| ≤ t/2: a node
/// inside leaves it by the nearer of its faces, through the plate's face (along ±axis, depth
/// t/2 − |h|) or the hole's wall (towards the axis, depth ρ − r). That is its exact signed
/// distance, the rim's corners included (outside nodes do not touch).
void findOrificeContacts(const GrainAsset& a, const RigidPose& pose, const Vec3& c,
                         const Vec3& axis, double r, double thickness,
                         std::vector<NodeContact>& out, NodeCheckStats& stats)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    const double half = 0.5 * thickness;
    // Clear of the plate: beyond either face, or within the hole.
    auto isClearOfPlate = [&](const Vec3& x, double reach) {
        const Vec3 offset = x - c;
        const double h = offset.dot(axis);
        return std::abs(h) > half + reach || (offset - h * axis).norm() + reach < r;
    };
    if (isClearOfPlate(pose.position, a.boundingRadius)) {
        stats.nodesCulled += count;
        return;
    }
    const Eigen::Matrix3d rotation = pose.orientation.toRotationMatrix();
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + pose.position;
            ++stats.nodesSampled;
            const Vec3 offset = x - c;
            const double h = offset.dot(axis);
            const Vec3 radial = offset - h * axis;
            const double rho = radial.norm();
            const double throughFace = half - std::abs(h), throughHole = rho - r;
            if (!(throughFace > 0.0 && throughHole > 0.0)) continue;
            ++stats.nodesInContact;
            NodeContact nc;
            nc.node = i;
            if (throughFace <= throughHole) {
                nc.depth = throughFace;
                nc.normal = h >= 0.0 ? axis : Vec3(-axis);
            } else {
                nc.depth = throughHole;
                nc.normal = -radial / rho;
            }
            nc.point = x + 0.5 * nc.depth * nc.normal;
            nc.area = a.nodes.areas[i];
            out.push_back(nc);
        }
    };
    auto isClear = [&](const NodeBlock& run) {
        return isClearOfPlate(rotation * run.center + pose.position, run.radius);
    };
    forEachBlockNotClear(a, isClear, visit, stats);
}

} // namespace

Vec3 Boundary::referencePoint() const
{
    switch (shape) {
    case BoundaryShape::Plane: return plane.point + displacement;
    case BoundaryShape::Sphere:
    case BoundaryShape::Cylinder:
    case BoundaryShape::Orifice: return center + displacement;
    case BoundaryShape::LevelSet: return pose.position + displacement;
    }
    return displacement;
}

bool Boundary::mayTouch(const Vec3& grainCenter, double grainRadius) const
{
    switch (shape) {
    case BoundaryShape::Plane: {
        const Plane p = movedPlane(*this);
        const double distance = p.signedDistance(grainCenter);
        if (distance > grainRadius || distance < -grainRadius - p.thickness) return false;
        if (!p.bounded()) return true;
        const Vec3 offset = grainCenter - p.point;
        return std::abs(offset.dot(p.axisU)) <= p.halfU + grainRadius &&
               std::abs(offset.dot(p.normal.cross(p.axisU))) <= p.halfV + grainRadius;
    }
    case BoundaryShape::Sphere:
        return (grainCenter - (center + displacement)).norm() <= radius + grainRadius;
    case BoundaryShape::LevelSet:
        return (grainCenter - (pose.position + displacement)).norm() <=
               asset->boundingRadius + grainRadius;
    case BoundaryShape::Cylinder: {
        const Vec3 offset = grainCenter - (center + displacement);
        return (offset - offset.dot(axis) * axis).norm() + grainRadius >= radius;
    }
    case BoundaryShape::Orifice: {
        const Vec3 offset = grainCenter - (center + displacement);
        const double h = offset.dot(axis);
        return std::abs(h) <= 0.5 * thickness + grainRadius &&
               (offset - h * axis).norm() + grainRadius >= radius;
    }
    }
    return false;
}

bool integratesPatches(BoundaryShape shape)
{
    return shape == BoundaryShape::Plane || shape == BoundaryShape::Sphere ||
           shape == BoundaryShape::LevelSet;
}

void findBoundaryContacts(const GrainAsset& a, const RigidPose& pose, const Boundary& b,
                          std::vector<NodeContact>& out, NodeCheckStats& stats,
                          CandidateBlocks* candidates, bool patches)
{
    if (patches && !integratesPatches(b.shape))
        throw std::logic_error("findBoundaryContacts: no patch quadrature against this shape");
    switch (b.shape) {
    case BoundaryShape::Plane:
        findPlaneContacts(a, pose, movedPlane(b), out, stats, patches);
        return;
    case BoundaryShape::Sphere:
        findSphereContacts(a, pose, b.center + b.displacement, b.radius, out, stats, patches);
        return;
    case BoundaryShape::LevelSet:
        findNodeContacts(a, pose, *b.asset, movedPose(b), out, stats, candidates, patches);
        return;
    case BoundaryShape::Cylinder:
        findCylinderContacts(a, pose, b.center + b.displacement, b.axis, b.radius, out, stats);
        return;
    case BoundaryShape::Orifice:
        findOrificeContacts(a, pose, b.center + b.displacement, b.axis, b.radius, b.thickness,
                            out, stats);
        return;
    }
}

} // namespace lsdem
