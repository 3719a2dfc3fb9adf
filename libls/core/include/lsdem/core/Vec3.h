/// @file Vec3.h
/// @brief The vector and matrix types of every lsdem library (Eigen's, in double): points,
///        forces and rotations alike, so a contact header needs no mesh header for them.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace lsdem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// @a v as a direction of unit length: normalised, unless it is already unit to rounding
/// (|‖v‖² − 1| ≤ 4ε), then returned bit for bit, so a direction written exactly and read back
/// is the same direction (normalising a normalised vector can move its last bit).
inline Vec3 unitVector(const Vec3& v)
{
    const double rounding = 4.0 * std::numeric_limits<double>::epsilon();
    return std::abs(v.squaredNorm() - 1.0) <= rounding ? v : v.normalized();
}

} // namespace lsdem
