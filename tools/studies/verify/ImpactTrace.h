/// @file ImpactTrace.h
/// @brief Steps a simulation through one impact and measures it as Chung & Ooi do: the
///        largest overlap and force, how long the bodies touch, and the force–time and
///        force–overlap curves.
#pragma once

#include "studies/verify/VerifyReport.h"

#include "lsdem/simulation/Simulation.h"

#include <functional>

namespace lsdem::verify {

struct ImpactTrace
{
    double maxOverlap = 0.0, peakForce = 0.0;
    double contactTime = 0.0;  ///< steps with a node in contact, times the step
    bool ended = false;        ///< the bodies touched and came apart within the steps allowed
    Series curve;              ///< time (from first contact), overlap, force
};

/// Step @a sim until its bodies have touched and come apart (no node in contact), at most
/// @a maxSteps steps. @a overlap and @a force say how deep the bodies overlap and how hard
/// they push at each step (the case's geometry: R − z for a ball on a floor, say).
ImpactTrace traceImpact(Simulation& sim, const std::function<double(const World&)>& overlap,
                        const std::function<double(const World&)>& force, long long maxSteps);

} // namespace lsdem::verify
