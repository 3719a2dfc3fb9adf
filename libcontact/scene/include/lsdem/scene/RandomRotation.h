/// @file RandomRotation.h
/// @brief Reproducible random numbers for building scenes: a uniform number in [0, 1) from a
///        64-bit Mersenne twister, and a uniformly distributed rotation (Shoemake's method).
///        The standard library's distributions are not specified bit for bit, so anything drawn
///        through them would differ between standard libraries; these are the same everywhere.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/core/Constants.h"

#include <cmath>
#include <random>

namespace lsdem {

/// A uniform number in [0, 1): the top 53 bits of the generator's next raw output.
inline double uniform01(std::mt19937_64& rng)
{
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// A uniformly distributed rotation from three numbers of @a uniform01 (any callable giving
/// uniform numbers in [0, 1)).
template <typename Uniform01>
Quat randomRotation(Uniform01&& uniform01)
{
    const double u1 = uniform01();
    const double u2 = 2.0 * kPi * uniform01();
    const double u3 = 2.0 * kPi * uniform01();
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return Quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3))
        .normalized();
}

/// A uniformly distributed rotation drawn from @a rng.
inline Quat randomRotation(std::mt19937_64& rng)
{
    return randomRotation([&rng] { return uniform01(rng); });
}

} // namespace lsdem
