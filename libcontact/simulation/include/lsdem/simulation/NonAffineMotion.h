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
#include "lsdem/simulation/PeriodicCell.h"

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

/// A grain's neighbour in a periodic cell: which grain, and the periods (−1, 0 or 1 along each
/// axis) of the image of it that is the neighbour.
struct PeriodicNeighbour
{
    int grain = 0;
    Vec3 periods = Vec3::Zero();
};

/// The same in periodic @a cell: a grain near a face has neighbours among the images of the
/// grains at the other face, each list in the order of the grains and then of their images.
std::vector<std::vector<PeriodicNeighbour>> neighboursWithin(const std::vector<Vec3>& centres,
                                                             const std::vector<double>& radii,
                                                             double reach, const PeriodicCell& cell);

/// D²min in a deforming periodic cell: an image neighbour sits at the grain's position plus
/// the periods times the cell's size then, @a referenceSize in the reference and
/// @a currentSize now (@a current unwrapped: Grain::unwrappedPosition).
std::vector<double> nonAffineDisplacement(const std::vector<Vec3>& reference,
                                          const Vec3& referenceSize,
                                          const std::vector<Vec3>& current,
                                          const Vec3& currentSize,
                                          const std::vector<std::vector<PeriodicNeighbour>>& neighbours);

} // namespace lsdem
