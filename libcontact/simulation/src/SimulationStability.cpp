// Simulation's stability check: each grain's stable step against the time step, after every
// step and, at the start, against the stiffest contact a touching grain can make.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/core/Error.h"
#include "lsdem/simulation/GhostDecomposition.h"

#include <tbb/parallel_for.h>

#include <climits>
#include <cmath>
#include <limits>
#include <sstream>

namespace lsdem {

namespace {

[[noreturn]] void throwNonFinite(const std::string& grain, long long step, double time)
{
    std::ostringstream s;
    s << "grain '" << grain << "' reached a non-finite state at step " << step << " (t = " << time
      << ")";
    throw Error("", s.str(),
                "lower the time step (time_step, or safety for \"auto\"); check the "
                "stiffnesses and masses for consistent units");
}

/// @a forecast: the limit is that of the stiffest contact the grain can make, checked at the
/// start for a grain touching something (no contact yet stiff enough to tell).
[[noreturn]] void throwUnstable(const std::string& grain, double dt, double limit, long long step,
                                double time, bool forecast)
{
    std::ostringstream s;
    s << "the time step " << dt << " exceeds the stability limit " << limit;
    if (forecast)
        s << " of the stiffest contact grain '" << grain
          << "' can make with what it touches at the start (a face of it pressed flat)";
    else
        s << " of the contacts of grain '" << grain << "' at step " << step << " (t = " << time
          << ")";
    s << ": the run would explode";
    std::ostringstream fix;
    fix << "set [simulation] time_step to at most " << 0.2 * limit
        << " (a fifth of the limit), or lower safety for \"auto\"";
    throw Error("", s.str(), fix.str());
}

} // namespace

void Simulation::checkStability(bool atStart)
{
    mStepLimits.resize(mWorld.grains.size());
    tbb::parallel_for(size_t(0), mWorld.grains.size(),
                      [&](size_t i) { mStepLimits[i] = stepLimitOf(i); });
    judgeStepLimits(mStepLimits, false);
    if (!atStart) return;
    // A grain touching something at the start (or about to: a candidate on the contact list)
    // may press it as hard as its stiffest contact within the next steps: grains resting on
    // each other just touching have no stiffness yet, and a step far too long for them would
    // throw them apart in the first steps, after the run has written its files. That estimate
    // is cautious by up to 2 in the step (a partner as heavy, and translation and rotation
    // bounded apart: StableStep.h), so only a step beyond twice it is refused: one that
    // contact cannot bear.
    std::vector<double> forecast = stiffestContactSteps(mWorld);
    for (size_t i = 0; i < mWorld.grains.size(); ++i)
        forecast[i] = integratesGrain(i) &&
                              mContacts.grainSlotsBegin(i) != mContacts.grainSlotsBegin(i + 1)
                          ? 2.0 * forecast[i]
                          : std::numeric_limits<double>::infinity();
    judgeStepLimits(forecast, true);
}

double Simulation::stepLimitOf(size_t i) const
{
    const Grain& g = mWorld.grains[i];
    if (!g.isFree() || !integratesGrain(i)) return std::numeric_limits<double>::infinity();
    const RigidBody& b = g.body;
    if (!b.pose.position.allFinite() || !b.velocity.allFinite() ||
        !b.angularMomentum.allFinite() || !b.pose.orientation.coeffs().allFinite())
        return std::numeric_limits<double>::quiet_NaN();
    // A bound that clears both the step and the least limit seen so far leaves the check's
    // outcome and that least limit as the exact limit would: most grains, most steps.
    const double lambda = mWorld.globalDamping;
    const double bound = stableStepLowerBound(mGrainStiffness[i], b, mLargestDampingRatio, lambda);
    if (bound >= mDt && bound >= mStabilityLimit) return bound;
    return stableStep(mGrainStiffness[i], b, mLargestDampingRatio, lambda);
}

void Simulation::judgeStepLimits(const std::vector<double>& limits, bool forecast)
{
    const World& w = mWorld;
    if (mGhosts) {
        checkStabilityOverRanks(limits, forecast);
        return;
    }
    for (size_t i = 0; i < limits.size(); ++i) {
        const double limit = limits[i];
        if (std::isnan(limit)) throwNonFinite(w.grains[i].name, w.step, w.time);
        if (!forecast) mStabilityLimit = std::min(mStabilityLimit, limit);
        if (mDt > limit) throwUnstable(w.grains[i].name, mDt, limit, w.step, w.time, forecast);
    }
}

void Simulation::checkStabilityOverRanks(const std::vector<double>& limits, bool forecast)
{
    const World& w = mWorld;
    const std::vector<int>& ids = mGhosts->globalIds();
    // This rank's first failing grain (ghosts are infinite) and smallest limit; then the
    // first failure in global order, as one process finds it, on every rank.
    OrderedTerm mine;
    mine.key[0] = LLONG_MAX;
    mine.key[1] = mGhosts->ranks().rank();
    mine.value[0] = std::numeric_limits<double>::infinity();
    size_t failing = 0;
    for (size_t i = 0; i < limits.size(); ++i) {
        const double limit = limits[i];
        if (std::isnan(limit) || mDt > limit) {
            mine.key[0] = ids[i];
            mine.value[1] = limit;
            failing = i;
            break;
        }
        mine.value[0] = std::min(mine.value[0], limit);
    }
    const std::vector<OrderedTerm> all = mGhosts->gatherSorted({mine});
    if (!forecast)
        for (const OrderedTerm& t : all) mStabilityLimit = std::min(mStabilityLimit, t.value[0]);
    const OrderedTerm& first = all.front();
    if (first.key[0] == LLONG_MAX) return;
    // Its name is known to its owner only.
    std::vector<char> name, names;
    if (first.key[1] == mGhosts->ranks().rank())
        name.assign(w.grains[failing].name.begin(), w.grains[failing].name.end());
    std::vector<size_t> starts;
    mGhosts->ranks().allGather(name, names, starts);
    const std::string grain(names.begin(), names.end());
    const double limit = first.value[1];
    if (std::isnan(limit)) throwNonFinite(grain, w.step, w.time);
    throwUnstable(grain, mDt, limit, w.step, w.time, forecast);
}

} // namespace lsdem
