/// @file DampingModel.h
/// @brief The damping sub-model: a viscous normal dashpot, as a fraction β of critical damping.
///        A contact of total normal stiffness K between bodies of effective mass m gets the
///        dashpot 2β·sqrt(m·K), shared between its point forces in proportion to their
///        stiffness.
#pragma once

namespace lsdem {

struct ViscousDamping
{
    double ratio = 0.0;  ///< β, fraction of critical damping (0: none)

    /// The ratio β for which a linear spring-dashpot rebounds at @a restitution times its
    /// impact speed: β = -ln e / sqrt(π² + ln² e). @a restitution in (0, 1]; 1 gives 0.
    static ViscousDamping fromRestitution(double restitution);

    /// c/k of every point force: 2β·sqrt(m/K), so Σ c_f = 2β·sqrt(m·K). 0 without damping
    /// or without stiffness.
    double dashpotPerStiffness(double effectiveMass, double totalStiffness) const;
};

/// ViscousDamping::fromRestitution(restitution).ratio.
double dampingRatioFromRestitution(double restitution);

} // namespace lsdem
