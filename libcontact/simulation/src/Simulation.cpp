#include "lsdem/simulation/Simulation.h"

#include "lsdem/ls/Stopwatch.h"
#include "lsdem/simulation/BroadPhase.h"
#include "lsdem/simulation/ContactDecomposition.h"
#include "lsdem/ls/Error.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <sstream>

namespace lsdem {

namespace {

ContactGrain contactView(const Grain& g, int index)
{
    ContactGrain c;
    c.asset = g.asset.get();
    c.pose = g.body.pose;
    c.velocity = g.motion == GrainMotion::Fixed ? Vec3::Zero() : g.body.velocity;
    c.angularVelocity = g.angularVelocity();
    c.index = index;
    c.mass = g.isFree() ? g.body.mass : 0.0;
    return c;
}

ContactGrain contactView(const Boundary& b)
{
    ContactGrain c;
    c.asset = b.asset.get();
    c.pose.position = b.referencePoint();
    c.pose.orientation = b.pose.orientation;
    c.velocity = b.velocity;
    c.mass = 0.0;
    return c;
}

/// Turn a prescribed grain by ω·dt (exact rotation about a fixed world axis).
void rotateBy(Quat& orientation, const Vec3& omega, double dt)
{
    const double angle = omega.norm() * dt;
    if (angle == 0.0) return;
    orientation = (Quat(Eigen::AngleAxisd(angle, omega.normalized())) * orientation).normalized();
}

/// YADE's non-viscous damping: each component loses λ·|F| against the motion.
Vec3 dampComponents(const Vec3& force, const Vec3& velocity, double lambda)
{
    Vec3 damped = force;
    for (int k = 0; k < 3; ++k) {
        const double sign = force[k] * velocity[k] > 0.0 ? 1.0 : force[k] * velocity[k] < 0.0 ? -1.0 : 0.0;
        damped[k] = force[k] * (1.0 - lambda * sign);
    }
    return damped;
}

} // namespace

Simulation::Simulation(World world, double dt, bool evaluateInitialForces,
                       bool recordContactForces, ContactDecomposition* decomposition)
    : mWorld(std::move(world)), mDt(dt), mRecordForces(recordContactForces),
      mStabilityLimit(std::numeric_limits<double>::infinity()), mDecomposition(decomposition)
{
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error("", "the time step must be a positive number", "check time_step");
    if (evaluateInitialForces) {
        evaluateForces(0.0);
        const Energies e = energies();
        mWorld.energy.initialTotal = e.kinetic + e.elastic + e.potential;
        // Grains that start in contact: a step too large for that contact would throw them
        // apart in the very first kick, before any later check could see the contact.
        checkStability();
    }
}

void Simulation::step()
{
    const double dt = mDt;
    const auto integrateStart = SteadyClock::now();
    // Servo walls choose this step's velocity from the state it starts from.
    updateServoVelocities(mWorld, dt);
    // Work of moving boundaries and prescribed grains: trapezoid over the step.
    double workBefore = 0.0;
    for (const Boundary& b : mWorld.boundaries) workBefore -= b.force.dot(b.velocity);
    for (const Grain& g : mWorld.grains)
        if (g.motion == GrainMotion::Prescribed)
            workBefore -= g.force.dot(g.body.velocity) + g.torque.dot(g.prescribedAngularVelocity);

    // Each grain moves on its own: parallel, and still the same numbers on any thread count.
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        Grain& g = mWorld.grains[i];
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
    });
    for (Boundary& b : mWorld.boundaries) b.displacement += b.velocity * dt;
    mWorld.time = static_cast<double>(mWorld.step + 1) * dt;  // no drift from summing dt
    ++mWorld.step;
    mCounters.integrateSeconds += secondsSince(integrateStart);

    evaluateForces(dt);

    const auto kickStart = SteadyClock::now();
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        Grain& g = mWorld.grains[i];
        if (g.isFree()) kick(g.body, g.force, g.torque, 0.5 * dt);
    });
    double workAfter = 0.0;
    for (const Boundary& b : mWorld.boundaries) workAfter -= b.force.dot(b.velocity);
    for (const Grain& g : mWorld.grains)
        if (g.motion == GrainMotion::Prescribed)
            workAfter -= g.force.dot(g.body.velocity) + g.torque.dot(g.prescribedAngularVelocity);
    mWorld.energy.boundaryWork += 0.5 * (workBefore + workAfter) * dt;
    ++mCounters.steps;
    checkStability();
    mCounters.integrateSeconds += secondsSince(kickStart);
}

void Simulation::evaluateForces(double slipStep)
{
    World& w = mWorld;
    const int n = static_cast<int>(w.grains.size());
    const auto broadStart = SteadyClock::now();
    if (mContacts.update(w)) ++mCounters.listRebuilds;
    std::vector<ContactSlot>& slots = mContacts.slots();
    const size_t pairSlots = mContacts.pairSlotCount();
    // Each body as the contact laws see it (pose, velocities), in parallel.
    mViews.resize(size_t(n));
    tbb::parallel_for(0, n, [&](int i) { mViews[size_t(i)] = contactView(w.grains[size_t(i)], i); });
    mBoundaryViews.clear();
    for (const Boundary& b : w.boundaries) mBoundaryViews.push_back(contactView(b));
    // Split over ranks, this rank evaluates its own slots and receives the others' after.
    const std::vector<char>* mine =
        mDecomposition ? &mDecomposition->assign(w, mContacts) : nullptr;
    mCounters.broadSeconds += secondsSince(broadStart);
    mCounters.candidatePairs += static_cast<long long>(pairSlots);
    mCounters.boundaryCandidates += static_cast<long long>(slots.size() - pairSlots);

    // Narrow phase and contact laws, one slot per task; nothing shared is written.
    const auto narrowStart = SteadyClock::now();
    const bool record = mRecordForces;
    const std::vector<ContactGrain>& views = mViews;
    const std::vector<ContactGrain>& boundaryViews = mBoundaryViews;
    tbb::parallel_for(size_t(0), slots.size(), [&](size_t k) {
        if (mine && !(*mine)[k]) return;
        ContactSlot& s = slots[k];
        ContactScratch& scratch = mScratch.local();  // this thread's buffers, reused
        s.stats = NodeCheckStats();
        s.forces.clear();
        std::vector<PointForce>* out = record ? &s.forces : nullptr;
        const Grain& gi = w.grains[s.first];
        if (s.boundary < 0) {
            const ContactModel& m = w.model(gi.material, w.grains[s.second].material);
            s.result = computePairContact(views[s.first], views[s.second], m, slipStep,
                                          s.pairHistory, s.stats, out, &scratch, &s.candidates);
        } else {
            const Boundary& b = w.boundaries[s.boundary];
            ContactSide side;
            side.tester = &views[s.first];
            side.other = &boundaryViews[s.boundary];
            side.history = s.boundaryHistory;
            side.contacts.swap(scratch.contacts[0]);
            side.contacts.clear();
            findBoundaryContacts(*gi.asset, gi.body.pose, b, side.contacts, s.stats);
            s.result = resolveContact(&side, 1, w.model(gi.material, b.material), slipStep, out,
                                      &scratch);
            side.contacts.swap(scratch.contacts[0]);
        }
    });
    mCounters.narrowSeconds += secondsSince(narrowStart);
    if (mDecomposition) mDecomposition->share(mContacts, record);

    // Sum each grain's slots in list order, grains in parallel: the same numbers whatever the
    // thread count (and the same as one pass over the slots in order).
    const auto reduceStart = SteadyClock::now();
    mGrainStiffness.resize(size_t(n));
    tbb::parallel_for(0, n, [&](int i) {
        Grain& g = w.grains[size_t(i)];
        Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
        Mat3 stiffness = Mat3::Zero();
        for (const GrainSlotRef* r = mContacts.grainSlotsBegin(size_t(i));
             r != mContacts.grainSlotsBegin(size_t(i) + 1); ++r) {
            const PairForces& f = slots[size_t(r->slot)].result;
            force += r->first ? f.forceOnFirst : f.forceOnSecond;
            torque += r->first ? f.torqueOnFirst : f.torqueOnSecond;
            stiffness += f.normalStiffness;
        }
        if (g.isFree()) {
            force += g.body.mass * w.gravity;
            if (w.globalDamping > 0.0) {
                force = dampComponents(force, g.body.velocity, w.globalDamping);
                torque = dampComponents(torque, g.body.angularVelocity(), w.globalDamping);
            }
        }
        g.force = force;
        g.torque = torque;
        mGrainStiffness[size_t(i)] = stiffness;
    });
    for (Boundary& b : w.boundaries) b.force = Vec3::Zero(), b.normalStiffness = b.normalDashpot = 0.0;
    mForces.clear();
    mContactNodes = 0;
    mElastic = 0.0;
    for (size_t k = 0; k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        const PairForces& r = s.result;
        mCounters.nodes += s.stats;
        mContactNodes += r.contactNodes;
        mElastic += r.elasticEnergy;
        if (s.boundary >= 0) {
            Boundary& b = w.boundaries[s.boundary];
            b.force += r.forceOnSecond;
            if (b.shape == BoundaryShape::Plane) {  // what a servo wall's gain is based on
                const double stiffness = b.plane.normal.dot(r.normalStiffness * b.plane.normal);
                const ViscousDamping damping =
                    w.model(w.grains[s.first].material, b.material).damping();
                b.normalStiffness += stiffness;
                b.normalDashpot +=
                    damping.dashpotPerStiffness(mViews[s.first].mass, stiffness) * stiffness;
            }
        }
        for (size_t f = 0; f < s.forces.size(); ++f) {
            const bool onFirst = static_cast<int>(f) < r.pointForcesOnFirst;
            mForces.push_back({s.forces[f].point, s.forces[f].force,
                               onFirst ? s.first : s.second});
        }
    }
    mCounters.integrateSeconds += secondsSince(reduceStart);
}

void Simulation::checkStability()
{
    const World& w = mWorld;
    // Each free grain's stable step limit (infinite without contacts; NaN if its state is no
    // longer finite), in parallel; then the verdict in grain order, so the message is the same
    // on any thread count.
    const size_t n = w.grains.size();
    std::vector<double> limits(n, std::numeric_limits<double>::infinity());
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        const Grain& g = w.grains[i];
        if (!g.isFree()) return;
        const RigidBody& b = g.body;
        if (!b.pose.position.allFinite() || !b.velocity.allFinite() ||
            !b.angularMomentum.allFinite() || !b.pose.orientation.coeffs().allFinite()) {
            limits[i] = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        if (mGrainStiffness[i].isZero()) return;
        // Stiffest direction of the grain's contacts: ω² = λ_max / m; explicit stepping is
        // stable for dt < 2/ω.
        Eigen::SelfAdjointEigenSolver<Mat3> solver;
        solver.computeDirect(mGrainStiffness[i], Eigen::EigenvaluesOnly);
        const double lambda = solver.eigenvalues().maxCoeff();
        if (lambda > 0.0) limits[i] = 2.0 * std::sqrt(b.mass / lambda);
    });
    for (size_t i = 0; i < n; ++i) {
        const Grain& g = w.grains[i];
        const double limit = limits[i];
        if (std::isnan(limit)) {
            std::ostringstream s;
            s << "grain '" << g.name << "' reached a non-finite state at step " << w.step
              << " (t = " << w.time << ")";
            throw Error("", s.str(),
                        "lower the time step (time_step, or safety for \"auto\"); check the "
                        "stiffnesses and masses for consistent units");
        }
        mStabilityLimit = std::min(mStabilityLimit, limit);
        if (mDt > limit) {
            std::ostringstream s;
            s << "the time step " << mDt << " exceeds the stability limit " << limit
              << " of the contacts of grain '" << g.name << "' at step " << w.step
              << " (t = " << w.time << "): the run would explode";
            std::ostringstream fix;
            fix << "set [simulation] time_step to at most " << 0.2 * limit
                << " (a fifth of the limit), or lower safety for \"auto\"";
            throw Error("", s.str(), fix.str());
        }
    }
}

std::vector<int> Simulation::grainContactCounts() const
{
    std::vector<int> counts(mWorld.grains.size(), 0);
    const std::vector<ContactSlot>& slots = mContacts.slots();
    for (size_t k = 0; k < mContacts.pairSlotCount(); ++k)
        if (slots[k].result.contactNodes > 0) {
            ++counts[size_t(slots[k].first)];
            ++counts[size_t(slots[k].second)];
        }
    return counts;
}

Energies Simulation::energies() const
{
    Energies e;
    for (const Grain& g : mWorld.grains) {
        if (!g.isFree()) continue;
        e.kinetic += g.body.kineticEnergy();
        e.potential -= g.body.mass * mWorld.gravity.dot(g.body.pose.position);
    }
    e.elastic = mElastic;
    e.boundaryWork = mWorld.energy.boundaryWork;
    e.dissipated = e.boundaryWork - (e.kinetic + e.elastic + e.potential -
                                     mWorld.energy.initialTotal);
    return e;
}

double automaticTimeStep(const World& world, double safety)
{
    double stiffest = 0.0;
    double largestArea = 0.0;
    for (const Grain& g : world.grains)
        for (double a : g.asset->nodes.areas) largestArea = std::max(largestArea, a);
    for (const ContactModel& m : world.models) {
        const double normal = m.normal().nodeStiffness(m.normalStiffness, largestArea);
        const double shear = m.normal().nodeStiffness(m.shearStiffness, largestArea);
        stiffest = std::max({stiffest, normal, shear});
    }
    double lightest = std::numeric_limits<double>::infinity();
    for (const Grain& g : world.grains) {
        if (!g.isFree()) continue;
        const double r = g.asset->boundingRadius;
        lightest = std::min({lightest, g.body.mass, g.body.principalInertia.minCoeff() / (r * r)});
    }
    if (!(stiffest > 0.0) || !std::isfinite(lightest))
        throw Error("", "cannot choose an automatic time step: no free grain or no contact stiffness",
                    "give [simulation] time_step explicitly");
    return safety * 2.0 * std::sqrt(lightest / stiffest);
}

} // namespace lsdem
