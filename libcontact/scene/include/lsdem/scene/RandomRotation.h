/// @file RandomRotation.h
/// @brief A uniformly distributed random rotation (Shoemake's method) from three uniform numbers
///        in [0, 1), drawn by the caller's @a uniform01 so each user keeps its own reproducible
///        generator (scene lattices, the studies' random orientations).
#pragma once

#include "lsdem/contact/RigidPose.h"

#include <cmath>

namespace lsdem {

template <typename Uniform01>
Quat randomRotation(Uniform01&& uniform01)
{
    constexpr double twoPi = 2.0 * 3.14159265358979323846;
    const double u1 = uniform01();
    const double u2 = twoPi * uniform01();
    const double u3 = twoPi * uniform01();
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return Quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3))
        .normalized();
}

} // namespace lsdem
