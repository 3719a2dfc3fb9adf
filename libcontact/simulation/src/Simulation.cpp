// Simulation: construction and the velocity-Verlet step. The force evaluation is in
// SimulationForces.cpp, the stability check in SimulationStability.cpp, the measures a run
// reads in SimulationMeasures.cpp.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/simulation/GhostDecomposition.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace lsdem {

namespace {

/// Turn a prescribed grain by ω·dt (exact rotation about a fixed world axis).
void rotateBy(Quat& orientation, const Vec3& omega, double dt)
{
    const double angle = omega.norm() * dt;
    if (angle == 0.0) return;
    orientation = (Quat(Eigen::AngleAxisd(angle, omega.normalized())) * orientation).normalized();
}

/// A deforming periodic cell @a cell stretched by 1 + ε̇·dt along each axis for this step (its
/// stress-controlled axes at the rate their stress asks); the stretch, which the grains'
/// positions in the cell follow (their velocities are what they have on top of that).
Vec3 stretchCell(PeriodicCell& cell, double dt)
{
    const Vec3 stretch = Vec3::Ones() + dt * cell.strainRate;
    if (cell.deforming()) {
        const Vec3 size = cell.size.cwiseProduct(stretch);
        const int a = cell.axisBelowLeastSize(size);
        if (a >= 0)
            throw Error("", std::string("the periodic cell would be strained to ") +
                                numberText(size[a]) + " along " + "xyz"[a] + ", " +
                                cell.leastSizeProblem(),
                        "start from a larger cell (more grains), or strain it less");
        cell.size = size;
    }
    return stretch;
}

/// The first half of grain @a g's step: a free grain's half kick and drift, a prescribed
/// grain's motion; a fixed grain stays.
void moveGrain(Grain& g, double dt)
{
    switch (g.motion) {
    case GrainMotion::Free:
        kick(g.body, g.force, g.torque, 0.5 * dt);
        drift(g.body, dt);
        break;
    case GrainMotion::Prescribed:
        g.body.pose.position += g.body.velocity * dt;
        rotateBy(g.body.pose.orientation, g.prescribedAngularVelocity, dt);
        break;
    case GrainMotion::Fixed: break;
    }
}

/// Grain @a g (not fixed) carried along by a deforming cell's @a stretch, and brought back
/// into the cell: a grain leaving through a face comes back through the other.
void keepInCell(Grain& g, const PeriodicCell& cell, const Vec3& stretch, bool deforms)
{
    if (deforms) {
        g.body.pose.position =
            cell.origin + (g.body.pose.position - cell.origin).cwiseProduct(stretch);
        g.wrapShift = g.wrapShift.cwiseProduct(stretch);
    }
    const Vec3 shift = cell.shiftInto(g.body.pose.position);
    if (!shift.isZero(0.0)) {
        g.body.pose.position += shift;
        g.wrapShift += shift;
    }
}

} // namespace

Simulation::Simulation(World world, double dt, bool evaluateInitialForces,
                       bool recordContactForces)
    : mWorld(std::move(world)), mDt(dt), mRecordForces(recordContactForces),
      mStabilityLimit(std::numeric_limits<double>::infinity()),
      mLargestDampingRatio(largestDampingRatio(mWorld))
{
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error("", "the time step must be a positive number", "check time_step");
    checkMembranes();
    if (evaluateInitialForces) {
        evaluateForces(0.0);
        const Energies e = energies();
        mWorld.energy.initialTotal = e.kinetic + e.elastic + e.potential;
        // Grains that start in contact: a step too large for that contact would throw them
        // apart in the very first kick, before any later check could see the contact.
        checkStability(true);
        judgeMembraneStep();
        judgeMembraneForecast();
    }
}

Simulation::Simulation(World world, double dt, bool evaluateInitialForces,
                       bool recordContactForces, GhostDecomposition& ghosts)
    : mWorld(std::move(world)), mDt(dt), mRecordForces(recordContactForces),
      mStabilityLimit(std::numeric_limits<double>::infinity()),
      mLargestDampingRatio(largestDampingRatio(mWorld)), mGhosts(&ghosts)
{
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error("", "the time step must be a positive number", "check time_step");
    checkMembranes();  // (every rank holds each membrane whole)
    for (const Grain& g : mWorld.grains) mHasPrescribed |= g.motion == GrainMotion::Prescribed;
    // The whole simulation's skin, so this rank's list is the one-process list's part.
    const double skin = mContacts.skinFor(mWorld);
    mContacts.fixSkin(skin);
    mContacts.restrictTo(&ghosts.owned());
    ghosts.distribute(mWorld, skin);
    mFreshlyDistributed = true;
    if (evaluateInitialForces) {
        evaluateForces(0.0);
        const Energies e = energies();
        mWorld.energy.initialTotal = e.kinetic + e.elastic + e.potential;
        checkStability(true);
        judgeMembraneStep();
        judgeMembraneForecast();
    }
}

double Simulation::exchangedSeconds() const
{
    if (!mGhosts) return 0.0;
    return mGhosts->counters().exchangeSeconds + mGhosts->counters().packSeconds;
}

bool Simulation::integratesGrain(size_t i) const
{
    return !mGhosts || mGhosts->owned()[i];
}

void Simulation::step()
{
    const double dt = mDt;
    const auto integrateStart = SteadyClock::now();
    const double integrateExchanged = exchangedSeconds();
    // Servo walls choose this step's velocity from the state it starts from.
    updateServoVelocities(mWorld, dt);
    // Work of moving boundaries and prescribed grains: trapezoid over the step.
    PeriodicCell& cell = mWorld.periodic;
    if (cell.servoed()) cell.steer();
    double workBefore = cell.strainRate.dot(mWorld.energy.cellMoment);
    for (const Boundary& b : mWorld.boundaries) workBefore -= b.force.dot(b.velocity);
    subtractPrescribedPower(workBefore);
    const Vec3 stretch = stretchCell(cell, dt);

    // Each grain moves on its own: parallel, and still the same numbers on any thread count.
    // A ghost is moved by its owner (and brought here before the forces).
    const bool wraps = cell.active(), deforms = cell.deforming();
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        if (!integratesGrain(i)) return;
        Grain& g = mWorld.grains[i];
        moveGrain(g, dt);
        if (wraps && g.motion != GrainMotion::Fixed) keepInCell(g, cell, stretch, deforms);
    });
    for (Boundary& b : mWorld.boundaries) b.displacement += b.velocity * dt;
    moveMembranes(dt);
    const double membraneWorkBefore = membraneExternalPower();
    mWorld.time = static_cast<double>(mWorld.step + 1) * dt;  // no drift from summing dt
    ++mWorld.step;
    mCounters.integrateSeconds +=
        secondsSince(integrateStart) - (exchangedSeconds() - integrateExchanged);

    evaluateForces(dt);
    const double membraneWorkAfter = membraneExternalPower();

    const auto kickStart = SteadyClock::now();
    const double kickExchanged = exchangedSeconds();
    // The second half kick and each grain's stable step limit after it, in one pass.
    mStepLimits.resize(mWorld.grains.size());
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        Grain& g = mWorld.grains[i];
        if (g.isFree() && integratesGrain(i)) kick(g.body, g.force, g.torque, 0.5 * dt);
        mStepLimits[i] = stepLimitOf(i);
    });
    double workAfter = cell.strainRate.dot(mWorld.energy.cellMoment);
    for (const Boundary& b : mWorld.boundaries) workAfter -= b.force.dot(b.velocity);
    subtractPrescribedPower(workAfter);
    kickMembranes(0.5 * dt);
    mWorld.energy.boundaryWork += 0.5 * (workBefore + workAfter) * dt +
                                  0.5 * (membraneWorkBefore + membraneWorkAfter) * dt;
    ++mCounters.steps;
    judgeStepLimits(mStepLimits, false);
    judgeMembraneStep();
    mCounters.integrateSeconds += secondsSince(kickStart) - (exchangedSeconds() - kickExchanged);
}

} // namespace lsdem
