/// @file NormalImpactReference.h
/// @brief What an elastic normal impact must give under a contact law P(δ): the one-body
///        equation m·δ'' = −P(δ) from δ = 0 at speed v. Energy gives the maximum overlap,
///        ½·m·v² = ∫₀^δmax P; the peak force is P(δmax); the contact lasts
///        t_c = 2·∫₀^δmax dδ / sqrt(v² − 2·U(δ)/m). For a power law P = κ·δ^p these are closed
///        forms (Gamma functions); for any other P, quadrature. The references of the
///        verification suite's normal impacts (Chung & Ooi tests 1 and 2), derived for
///        lsdem's laws: the adapted law on a sphere is a Winkler foundation, P = π·kn*·R·δ² on
///        a wall, not Hertz's δ^(3/2).
#pragma once

#include <functional>
#include <vector>

namespace lsdem::verify {

struct NormalImpact
{
    double maxOverlap = 0.0;   ///< δmax, length
    double peakForce = 0.0;    ///< P(δmax), force
    double contactTime = 0.0;  ///< time
};

/// P = @a kappa·δ^@a exponent, mass @a mass, impact speed @a speed (closed forms:
/// δmax = ((p+1)·m·v²/(2κ))^(1/(p+1)), t_c = 2·(δmax/v)·√π·Γ(1 + 1/(p+1))/Γ(½ + 1/(p+1))).
NormalImpact powerLawImpact(double kappa, double exponent, double mass, double speed);

/// Any increasing force law @a force(δ) (δmax found by bisection on the energy; the integrals
/// by Gauss–Legendre, with δ = δmax·(1 − s²) to remove the root's singularity at δmax).
/// @a overlapScale: an overlap beyond δmax, to bracket it.
NormalImpact forceLawImpact(const std::function<double(double)>& force, double mass,
                            double speed, double overlapScale);

/// The same for a law that is zero up to the overlap @a onset (where the first node touches)
/// and whose energy U(δ) = ∫ P is given too (@a energy): piecewise laws such as a node sum,
/// whose kinks a single quadrature rule would not resolve (the contact time, from the onset
/// back to it, by 256 Gauss–Legendre panels).
NormalImpact piecewiseLawImpact(const std::function<double(double)>& force,
                                const std::function<double(double)>& energy, double onset,
                                double mass, double speed, double overlapScale);

/// The impact's course in time, for figures: t, δ and P(δ) every @a step until the body
/// leaves (classical Runge–Kutta on m·δ'' = −P(δ)).
std::vector<std::vector<double>> impactCourse(const std::function<double(double)>& force,
                                              double mass, double speed, double step);

} // namespace lsdem::verify
