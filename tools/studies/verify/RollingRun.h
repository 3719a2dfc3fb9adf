/// @file RollingRun.h
/// @brief A ball thrown flat onto a floor under gravity, measured as it slides and then rolls
///        (the slide-to-roll case and the convergence case share it).
#pragma once

#include "studies/verify/VerifyCases.h"

#include <memory>

namespace lsdem::verify {

struct RollingRun
{
    double slipEnd = -1.0;        ///< when the contact point's slip first reached zero
    double speedAtSlipEnd = 0.0;  ///< the centre's speed then
    double deceleration = 0.0;    ///< of the centre while rolling (least squares over the roll)
    double finalSpeed = 0.0;      ///< at the end of the roll
    double highestRise = 0.0;     ///< of the centre above R while rolling (a hop if > 0)
    double mass = 0.0;
    double frictionBySlipEnd = 0.0;     ///< energy friction took by the slip's end
    double frictionWhileRolling = 0.0;  ///< and after it, to the end
    double timeStep = 0.0;
    Series trace;                 ///< time, speed, slip, height − R
};

/// @a ball set on a floor at its resting overlap, at speed @a speed without spin, under the
/// setup's gravity, with law @a f, friction @a friction and restitution @a restitution; slides,
/// then rolls for @a rollTime; the nodes taken as points or as patches (@a quadrature).
RollingRun slideAndRoll(Context& c, const std::shared_ptr<const GrainAsset>& ball, Formulation f,
                        double speed, double friction, double restitution, double rollTime,
                        NodeQuadrature quadrature = NodeQuadrature::Point);

} // namespace lsdem::verify
