/// @file SphereContactReference.h
/// @brief The exact continuum-limit force between two equal frictionless spheres pressed
///        together, for the adapted formulation with one-way node testing (SCIENCE.md §3):
///        P(δ) = kn* ∫_cap d(x) (n(x)·e) dA over the part of sphere i inside sphere j.
#pragma once

namespace lsdem {

/// P for spheres of radius @a radius whose centres are 2R - @a overlap apart, with traction
/// stiffness @a knStar (force/length³). With u = cos θ on sphere i (θ from the centre line),
/// ρ = sqrt(R² + h² - 2Rh u), d = R - ρ, n·e = (h - R u)/ρ, dA = 2πR² du, integrated over
/// u ∈ [h/(2R), 1] by 64-point Gauss–Legendre (the integrand is smooth there).
double exactSphereContactForce(double radius, double overlap, double knStar);

/// The same two spheres under the volume law (F = kv·Σ d_a·A_a along the mean normal): its
/// continuum limit kv ∫_cap d dA, the integral above without the factor n·e (by symmetry the
/// mean normal is e). Larger than the adapted force by about δ/(6R) (0.34 % at δ/R = 0.02).
double exactSphereVolumeForce(double radius, double overlap, double kv);

/// The leading-order value (π/2)·kn*·R·δ², for small δ/R.
double leadingOrderSphereContactForce(double radius, double overlap, double knStar);

} // namespace lsdem
