/// @file PointForce.h
/// @brief A force on a grain at a world point: what every contact law produces, so forces and
///        torques (and the contact forces written for ParaView) follow from one list.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem {

/// A force on grain A at a world point; @a node is the node it came from (-1 if pooled).
struct PointForce
{
    int node = -1;
    Vec3 force = Vec3::Zero();
    Vec3 point = Vec3::Zero();
    /// dF/dd of the normal law that made it (force/length): for contact damping, the
    /// elastic energy ½|F|²/k and the stable time step.
    double stiffness = 0.0;
};

} // namespace lsdem
