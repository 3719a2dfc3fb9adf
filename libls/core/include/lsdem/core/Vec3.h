/// @file Vec3.h
/// @brief The vector and matrix types of every lsdem library (Eigen's, in double): points,
///        forces and rotations alike, so a contact header needs no mesh header for them.
#pragma once

#include <Eigen/Core>

namespace lsdem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

} // namespace lsdem
