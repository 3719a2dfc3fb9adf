/// @file BeverlooFit.h
/// @brief What the silo case measures a discharge against: a steady mass flow from the mass
///        discharged over time, and Beverloo's law fitted to the flows through orifices of
///        several sizes,
///
///     W = C·ρ_b·sqrt(g)·(D − k·d)^(5/2)
///
/// (Beverloo, Leniger & van de Velde, Chem. Eng. Sci. 15, 1961: W the mass flow through a
/// circular orifice of diameter D in a flat floor, ρ_b the bulk density, d the grain size; C
/// about 0.55–0.65 and k about 1.5 for spheres, up to ~3 for angular grains, as surveyed by
/// Nedderman, Statics and Kinematics of Granular Materials, 1992). With the exponent 5/2,
/// W^(2/5) is a straight line in D: its slope gives C, its root k·d.
#pragma once

#include <vector>

namespace lsdem::verify {

/// A least-squares straight line y = slope·x + intercept, and how well it fits.
struct LineFit
{
    double slope = 0.0, intercept = 0.0;
    double rSquared = 0.0;  ///< 1 − residual / total sum of squares (1: every point on it)
    /// The least-squares estimates' variances and covariance, with the residuals' variance
    /// σ² = Σr²/(n − 2): σ²/Sxx, σ²·(1/n + x̄²/Sxx), −x̄·σ²/Sxx. NaN for two points.
    double slopeVariance = 0.0, interceptVariance = 0.0, covariance = 0.0;
    int degreesOfFreedom = 0;  ///< n − 2
};

/// The least-squares line through (@a x, @a y) (at least two points, x not all equal).
LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y);

/// One orifice's steady discharge.
struct Discharge
{
    double diameter = 0.0;  ///< D, length
    double massFlow = 0.0;  ///< W, mass/time
};

struct BeverlooFit
{
    double c = 0.0;         ///< Beverloo's C
    double k = 0.0;         ///< the empty annulus, in grain sizes
    double rSquared = 0.0;  ///< of W^(2/5) against D
    /// The 95 % intervals of C and k from the line's uncertainty (Student's t for n − 2
    /// degrees of freedom). C depends on the slope alone and grows with it, so its interval is
    /// the slope's interval mapped through C(s); k·d is the ratio −intercept/slope, whose
    /// interval is Fieller's (every k whose line through the root is within t standard
    /// errors of the fit). Both are asymmetric about the estimate. NaN for two orifices,
    /// whose line is exact; k's ends are ∓infinity where the slope itself is not significant.
    double cLow95 = 0.0, cHigh95 = 0.0, kLow95 = 0.0, kHigh95 = 0.0;
};

/// Beverloo's flow W = C·ρ_b·sqrt(g)·(D − k·d)^(5/2) through an orifice of diameter @a diameter,
/// for an empty annulus k·d = @a emptyAnnulus (below the diameter).
double beverlooFlow(double c, double bulkDensity, double gravity, double diameter,
                    double emptyAnnulus);

/// Beverloo's law with the exponent 5/2 fitted to @a flows (at least two diameters) for bulk
/// density @a bulkDensity, gravity @a gravity and grain size @a grainSize.
BeverlooFit fitBeverloo(const std::vector<Discharge>& flows, double bulkDensity, double gravity,
                        double grainSize);

/// The exponent n of W ∝ (D − k·d)^n that fits @a flows best in logarithms, for a given
/// k·d = @a emptyAnnulus (below the smallest D): a check that 5/2 is the flows' own exponent.
double fittedExponent(const std::vector<Discharge>& flows, double emptyAnnulus);

} // namespace lsdem::verify
