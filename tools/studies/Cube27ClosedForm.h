/// @file Cube27ClosedForm.h
/// @brief The continuum limit of the 3×3×3 stack: nine columns of wall–sphere, two
///        sphere–sphere and sphere–floor contacts in series (SCIENCE.md §3), closed form and
///        exact.
#pragma once

#include "lsdem/contact/NormalModel.h"

#include <cmath>

namespace lsdem {

/// δ = kCube27Column·d_w for a column of wall, two sphere–sphere contacts and floor: the
/// sphere–sphere overlap is √2 times the wall's (equal forces: π·k·R·d_w² = (π/2)·k·R·d_s²).
inline const double kCube27Column = 2.0 + 2.0 * std::sqrt(2.0);

/// Closed form (parabolic caps, small δ/R) of the adapted law: each of the 9 columns is
/// wall–sphere (P = π·k·R·d_w², exact for a plane), sphere–sphere twice (P = (π/2)·k·R·d_s²)
/// and sphere–floor in series, so d_s = √2·d_w, δ = (2 + 2√2)·d_w and
/// P = 9·π·k·R·δ² / (2 + 2√2)².
double cube27ClosedForm(double radius, double delta, double knStar);

/// The same continuum limit without the parabolic approximation of the sphere–sphere caps:
/// the sphere–sphere force is @a law's NormalModel::continuumSphereForce (a 1-D quadrature;
/// every law's sphere–plane force is π·k·R·d_w²), and d_w is found so that
/// 2·d_w + 2·d_s = δ with equal forces in every contact of a column. @a knStar is the law's
/// traction stiffness (NormalModel::tractionStiffness); not for a law without one.
double cube27ExactForce(double radius, double delta, double knStar,
                        Formulation law = Formulation::Adapted);

} // namespace lsdem
