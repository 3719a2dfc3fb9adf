// How long a run goes and how often it writes, from the scene's end condition and output
// periods (private to the run library).
#pragma once

#include "lsdem/run/RunEnd.h"
#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

#include <string>

namespace lsdem::runplan {

/// Steps between outputs for a period in time units (at least one step).
long long stepsPer(double period, double dt);

/// The end check is public (lsdem/run/RunEnd.h); the run driver finds it here too.
using lsdem::endReached;

/// The number of steps the end condition implies (a double: an absurd end_time must not
/// overflow), or -1 if it cannot be known in advance.
double plannedSteps(const Scene& scene, const World& w, double dt);

/// "42s", "3m07s", "2h05m", "12d", "3.2e+05 years".
std::string formatDuration(double seconds);

/// A warning for a run too long to be meant (more than a billion steps or a week at
/// @a secondsPerStep), naming the end condition, the step count and the time; "" otherwise.
std::string longRunWarning(const Scene& scene, double planned, double dt, double secondsPerStep);

} // namespace lsdem::runplan
