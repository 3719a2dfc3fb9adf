/// @file PlaneContact.h
/// @brief Contact of a grain with a rigid plane (a wall): the grain's nodes behind the plane
///        become NodeContacts with depth = distance behind it and the plane's normal, so every
///        formulation of NormalForce.h applies unchanged.
#pragma once

#include "lsdem/contact/NodeContact.h"

#include <vector>

namespace lsdem {

struct Plane
{
    Vec3 point = Vec3::Zero();      ///< a point on the plane, world
    Vec3 normal = Vec3::UnitZ();    ///< unit, pointing to the side where grains live

    double signedDistance(const Vec3& x) const { return (x - point).dot(normal); }
};

/// Append every node of grain @a a (at @a pose) behind @a plane, in node order. The contact
/// point is halfway between the node and the plane.
void findPlaneContacts(const GrainAsset& a, const RigidPose& pose, const Plane& plane,
                       std::vector<NodeContact>& out, NodeCheckStats& stats);

} // namespace lsdem
