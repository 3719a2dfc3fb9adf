/// @file RigidPose.h
/// @brief Where a grain is: the position of its centroid and the rotation from its asset
///        (principal) frame to the world, as a unit quaternion.
#pragma once

#include "lsdem/core/Vec3.h"

#include <Eigen/Geometry>

namespace lsdem {

using Quat = Eigen::Quaterniond;

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
