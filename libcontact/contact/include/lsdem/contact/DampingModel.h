/// @file DampingModel.h
/// @brief The damping sub-model: a viscous dashpot on the approach of the two bodies at a
///        contact, calibrated so that an impact rebounds at the coefficient of restitution e
///        the user gave, whatever the contact's force–penetration relation.
///
/// The dashpot of a contact of stiffness K = dP/dδ between bodies of effective mass m is
/// c = 2β·sqrt(m·K) (as Tsuji et al. 1992 did for Hertz), and it may push but never pull: the
/// elastic and viscous forces together are not allowed to attract (a dashpot that pulls holds
/// a leaving body back, and holds it hardest where a contact of discrete nodes has one node
/// left, whose stiffness does not vanish with its depth as the continuum's does). For a force
/// growing as a power P = κ·δ^p this makes the rebound independent of the impact speed: with
/// x = δ/δ₀ and τ = t·v₀/δ₀ (δ₀ = (m·v₀²/κ)^(1/(p+1))) an impact is the one-body equation
///
///     x'' = −max(0, x^p + 2β·sqrt(p·x^(p−1))·x'),   x(0) = 0, x'(0) = 1,
///
/// whose rebound speed −x' when x returns to 0 is e(β, p): β must be chosen for the law's
/// exponent p (a flat face on a wall: p = 1; a sphere under the adapted, original or volume
/// law: p = 2). The exponent of a contact is read from its state, p = δ_max·K/P (δ_max the
/// deepest node, K and P the stiffness and elastic force along the contact's normal; exact for
/// a power law), and β(e, p) comes from a table over p ∈ [1, 4] made once per restitution by
/// solving the equation above.
#pragma once

#include <array>

namespace lsdem {

class ViscousDamping
{
public:
    /// Exponents of the table: p = 1 + k·kExponentStep for k < kTableSize.
    static constexpr int kTableSize = 25;
    static constexpr double kExponentStep = 0.125;
    static constexpr double kLargestExponent = 1.0 + (kTableSize - 1) * kExponentStep;

    /// No damping (restitution 1).
    ViscousDamping() = default;
    /// Calibrated for @a restitution in (0, 1]. @throw std::invalid_argument outside it.
    explicit ViscousDamping(double restitution);

    double restitution() const { return mRestitution; }
    bool active() const { return mRestitution < 1.0; }

    /// β for a contact whose elastic force locally grows as δ^@a exponent (clamped to
    /// [1, kLargestExponent]; interpolated in the table).
    double ratio(double exponent) const;
    /// The largest β of any exponent: what the time step must allow for.
    double largestRatio() const { return mLargestRatio; }
    /// The dashpot c = 2β(p)·sqrt(m·K) of a contact of stiffness @a stiffness (force/length)
    /// between bodies of effective mass @a effectiveMass. 0 without damping or stiffness.
    double dashpot(double effectiveMass, double stiffness, double exponent) const;

private:
    double mRestitution = 1.0;
    double mLargestRatio = 0.0;
    std::array<double, kTableSize> mRatios{};  ///< β at p = 1 + k·kExponentStep
};

/// The coefficient of restitution of the one-body equation above for ratio @a ratio ≥ 0 and
/// exponent @a exponent ≥ 1, by classical Runge–Kutta (2000 steps per unit of time; relative
/// error up to 2e-4, from the force's kink where it lets go). 0 if the body never leaves.
double restitutionOfImpact(double ratio, double exponent);

/// The β for which restitutionOfImpact(β, @a exponent) is @a restitution in (0, 1] (0 for 1).
double dampingRatioFor(double restitution, double exponent);

} // namespace lsdem
