/// @file FreeRotationReference.h
/// @brief The torque-free rotation of a rigid body with principal moments I₁ < I₂ < I₃
///        (Euler's equations, solved by Jacobi's elliptic functions): a body spun about its
///        intermediate axis turns over and back (the tennis-racket or Dzhanibekov effect), its
///        spin about that axis, ω₂ = A·sn(λt, k), changing sign every 2K(k)/λ. Energy and the
///        angular momentum are conserved. The reference of the verification suite's free
///        rotation case.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem::verify {

/// The complete elliptic integral of the first kind K(k), modulus @a k in [0, 1), by the
/// arithmetic–geometric mean: K = π / (2·AGM(1, sqrt(1 − k²))).
double completeEllipticK(double k);

/// The time between successive changes of sign of the spin about the intermediate axis, for
/// principal moments @a moments (ascending, distinct) and body-frame spin @a omega:
/// 2K(k)/λ with, for L² > 2E·I₂, λ² = (I₃ − I₂)(L² − 2E·I₁)/(I₁I₂I₃) and
/// k² = (I₂ − I₁)(2E·I₃ − L²)/((I₃ − I₂)(L² − 2E·I₁)), and for L² < 2E·I₂ the same with
/// I₁ and I₃ exchanged. @throw std::invalid_argument for moments not ascending or a spin on
/// the separatrix (L² = 2E·I₂: it never flips back).
double intermediateAxisFlipTime(const Vec3& moments, const Vec3& omega);

} // namespace lsdem::verify
