/// @file PlaneContact.h
/// @brief Contact of a grain with a rigid plane (a wall): the grain's nodes behind the plane
///        become NodeContacts with depth = distance behind it and the plane's normal, so every
///        formulation of NormalModel.h applies unchanged.
#pragma once

#include "lsdem/contact/NodeContact.h"

#include <cmath>
#include <limits>
#include <vector>

namespace lsdem {

struct Plane
{
    Vec3 point = Vec3::Zero();      ///< a point on the plane, world
    Vec3 normal = Vec3::UnitZ();    ///< unit, pointing to the side where grains live
    /// Optional finite patch: a node counts only if its offset from @a point along @a axisU
    /// and along normal × axisU is within ±halfU and ±halfV, and it is less than
    /// @a thickness behind the plane. Infinite by default.
    Vec3 axisU = Vec3::UnitX();     ///< unit, perpendicular to normal
    double halfU = std::numeric_limits<double>::infinity();
    double halfV = std::numeric_limits<double>::infinity();
    double thickness = std::numeric_limits<double>::infinity();

    double signedDistance(const Vec3& x) const { return (x - point).dot(normal); }
    bool bounded() const { return std::isfinite(halfU) || std::isfinite(halfV); }
    /// Whether @a x, at signed distance @a distance, lies within the patch and its thickness.
    bool withinPatch(const Vec3& x, double distance) const
    {
        if (-distance > thickness) return false;
        if (!bounded()) return true;
        const Vec3 offset = x - point;
        return std::abs(offset.dot(axisU)) <= halfU &&
               std::abs(offset.dot(normal.cross(axisU))) <= halfV;
    }
};

/// Append every node of grain @a a (at @a pose) behind @a plane, in node order. The contact
/// point is halfway between the node and the plane. With @a patches, every node whose patch
/// reaches behind the plane, its contact integrated over the patch (PatchQuadrature.h; @a a
/// must carry its node shapes).
void findPlaneContacts(const GrainAsset& a, const RigidPose& pose, const Plane& plane,
                       std::vector<NodeContact>& out, NodeCheckStats& stats,
                       bool patches = false);

} // namespace lsdem
