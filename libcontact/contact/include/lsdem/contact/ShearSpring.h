/// @file ShearSpring.h
/// @brief The tangential force of one contact node, with history: the stored shear force is
///        turned onto the current tangent plane (keeping its size), incremented by -k_t·Δu_t,
///        and capped by Coulomb's μ·|F_n|.
#pragma once

#include "lsdem/ls/TriangleMesh.h"

namespace lsdem {

/// @param stored   shear force from the last step (zero for a node just entering contact)
/// @param normal   current unit contact normal
/// @param slip     relative displacement of the contact point in the step (any direction;
///                 only its tangential part counts)
/// @param stiffness k_t: ks (original) or ks*·A_a (adapted), times the testing weight
/// @param limit    μ·|F_n|, the largest shear the node can carry
/// @return the new shear force (tangent to @a normal, at most @a limit long)
Vec3 updateShearForce(const Vec3& stored, const Vec3& normal, const Vec3& slip,
                      double stiffness, double limit);

} // namespace lsdem
