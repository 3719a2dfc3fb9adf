/// @file RigidPose.h
/// @brief Where a grain is: the position of its centroid and the rotation from its asset
///        (principal) frame to the world, as a unit quaternion.
#pragma once

#include "lsdem/core/Vec3.h"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace lsdem {

using Quat = Eigen::Quaterniond;

/// @a q as a rotation, of unit length: normalised, unless it is already unit to rounding
/// (|‖q‖² − 1| ≤ 4ε), then returned as it is, bit for bit. Normalising a normalised quaternion
/// can move its last bit, so a pose written exactly and read back would not be the same pose.
inline Quat unitQuaternion(const Quat& q)
{
    const double rounding = 4.0 * std::numeric_limits<double>::epsilon();
    return std::abs(q.squaredNorm() - 1.0) <= rounding ? q : q.normalized();
}

struct RigidPose
{
    Vec3 position = Vec3::Zero();       ///< world position of the asset frame's origin (centroid)
    Quat orientation = Quat::Identity();  ///< asset frame -> world, unit

    Vec3 toWorld(const Vec3& local) const { return orientation * local + position; }
    Vec3 toLocal(const Vec3& world) const { return orientation.conjugate() * (world - position); }
    Vec3 directionToWorld(const Vec3& local) const { return orientation * local; }
    Vec3 directionToLocal(const Vec3& world) const { return orientation.conjugate() * world; }
};

} // namespace lsdem
