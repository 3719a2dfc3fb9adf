/// @file GlobalDamping.h
/// @brief The world's global (non-viscous) damping, shared by the grains and the membranes'
///        vertices: what it leaves of a force and what it takes over a step.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem {

/// YADE's non-viscous damping: each component loses λ·|F| against the motion.
inline Vec3 dampComponents(const Vec3& force, const Vec3& velocity, double lambda)
{
    Vec3 damped = force;
    for (int k = 0; k < 3; ++k) {
        const double sign = force[k] * velocity[k] > 0.0 ? 1.0 : force[k] * velocity[k] < 0.0 ? -1.0 : 0.0;
        damped[k] = force[k] * (1.0 - lambda * sign);
    }
    return damped;
}

/// What dampComponents takes from a body moving at @a velocity over @a dt: each component's
/// λ·|F_k| against the motion, λ·Σ|F_k·v_k|·dt.
inline double dampedWork(const Vec3& force, const Vec3& velocity, double lambda, double dt)
{
    return lambda * force.cwiseProduct(velocity).cwiseAbs().sum() * dt;
}

} // namespace lsdem
