/// @file RigidBody.h
/// @brief Explicit rigid-body time stepping in a grain's principal frame: velocity Verlet for
///        translation and, for rotation, a symplectic splitting of the free rigid body into
///        exact rotations about the principal axes (1, 2, 3, 2, 1). Without torques the world
///        angular momentum is kept to round-off and the energy error stays bounded, O(dt²).
#pragma once

#include "lsdem/contact/RigidPose.h"

namespace lsdem {

struct RigidBody
{
    RigidPose pose;                        ///< centroid and asset(principal)-to-world rotation
    Vec3 velocity = Vec3::Zero();          ///< of the centroid, world
    Vec3 angularMomentum = Vec3::Zero();   ///< about the centroid, world
    double mass = 1.0;
    Vec3 principalInertia = Vec3::Ones();  ///< I1, I2, I3 in the principal frame (> 0)

    /// World angular velocity ω = R I⁻¹ Rᵀ L.
    Vec3 angularVelocity() const;
    /// Set L from a world angular velocity.
    void setAngularVelocity(const Vec3& omega);
    /// Translational plus rotational kinetic energy.
    double kineticEnergy() const;
};

/// Half-step kick: v += F/m·dt/2, L += τ·dt/2 (world force and torque about the centroid).
void kick(RigidBody& body, const Vec3& force, const Vec3& torque, double halfStep);

/// Full-step drift: x += v·dt; the orientation and body-frame angular momentum follow the free
/// rigid-body flow, split as exact rotations about axes 1, 2, 3, 2, 1 (symmetric, so
/// time-reversible and second order).
void drift(RigidBody& body, double dt);

} // namespace lsdem
