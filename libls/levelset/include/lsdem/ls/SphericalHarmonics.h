/// @file SphericalHarmonics.h
/// @brief Real spherical harmonics Y_lm(θ, φ), orthonormal on the unit sphere
///        (∫ Y_lm Y_l'm' dΩ = δ_ll' δ_mm'), without the Condon–Shortley phase: the basis of the
///        generated grain surfaces (GrainGenerator.h).
#pragma once

#include <vector>

namespace lsdem {

/// Index of (l, m), -l <= m <= l, in the arrays below: l² + l + m.
inline int harmonicIndex(int l, int m) { return l * l + l + m; }

/// Every Y_lm for l = 0 .. @a maxDegree at the direction of polar angle @a theta (from +z) and
/// azimuth @a phi, into @a values (size (maxDegree + 1)², indexed by harmonicIndex). For m > 0
/// Y_lm ∝ cos(mφ), for m < 0 Y_lm ∝ sin(|m|φ). The associated Legendre functions come from the
/// stable normalized recurrences (no factorials), accurate to a few ulps up to degree ~100.
void realSphericalHarmonics(int maxDegree, double theta, double phi, std::vector<double>& values);

} // namespace lsdem
