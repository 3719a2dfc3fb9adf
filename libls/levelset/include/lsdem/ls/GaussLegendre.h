/// @file GaussLegendre.h
/// @brief Gauss–Legendre quadrature nodes and weights, for the closed-form references
///        (ellipsoid area, the two-sphere contact force).
#pragma once

#include <vector>

namespace lsdem {

/// The @a n nodes @a x and weights @a w of Gauss–Legendre quadrature on [-1, 1] (exact for
/// polynomials of degree 2n-1), by Newton's method on the Legendre recurrence.
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w);

} // namespace lsdem
