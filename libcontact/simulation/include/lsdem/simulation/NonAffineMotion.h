/// @file NonAffineMotion.h
/// @brief How far each grain has moved otherwise than its neighbourhood as a whole: the
///        non-affine displacement D²min of Falk & Langer (Phys. Rev. E 57, 7192, 1998), with its
///        neighbours taken in a reference configuration.
///
/// For grain i with neighbours j, D_ij = X_j − X_i in the reference and d_ij = x_j − x_i now,
/// D²min_i = min over 3×3 matrices J of Σ_j |d_ij − J·D_ij|²: what is left of the neighbours'
/// motion relative to i once the best local affine deformation J is taken out (0 when the
/// neighbourhood moved affinely, whatever it did; units length²). J = X·Y⁺ with X = Σ d⊗D and
/// Y = Σ D⊗D, Y⁺ its pseudo-inverse (a flat or a linear neighbourhood fixes J only in its own
/// directions: the others cost nothing).
#pragma once

#include "lsdem/core/Vec3.h"

#include <vector>

namespace lsdem {

/// The grains near each grain in @a centres: j with |X_j − X_i| < @a reach·(r_i + r_j), r the
/// @a radii (e.g. bounding radii: the grains that touch or nearly), each list ascending.
std::vector<std::vector<int>> neighboursWithin(const std::vector<Vec3>& centres,
                                               const std::vector<double>& radii, double reach);

/// D²min of every grain from its @a neighbours (indices into both position lists) between
/// the @a reference positions and the @a current ones; 0 for a grain without neighbours.
std::vector<double> nonAffineDisplacement(const std::vector<Vec3>& reference,
                                          const std::vector<Vec3>& current,
                                          const std::vector<std::vector<int>>& neighbours);

} // namespace lsdem
