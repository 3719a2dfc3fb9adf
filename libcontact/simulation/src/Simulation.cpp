#include "lsdem/simulation/Simulation.h"

#include "lsdem/ls/Stopwatch.h"
#include "lsdem/simulation/BroadPhase.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/ls/Error.h"

#include <tbb/parallel_for.h>

#include <climits>
#include <cmath>
#include <cstring>
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

/// Whether every number of @a r is +0 (bit for bit): the result of a slot without contact,
/// which added to a sum that starts at +0 changes nothing.
bool isEmpty(const PairForces& r)
{
    if (r.contactNodes != 0 || r.pointForcesOnFirst != 0) return false;
    static const double zeros[9] = {};
    const auto zero = [](const double* p, size_t n) {
        return std::memcmp(p, zeros, n * sizeof(double)) == 0;
    };
    return zero(r.forceOnFirst.data(), 3) && zero(r.torqueOnFirst.data(), 3) &&
           zero(r.forceOnSecond.data(), 3) && zero(r.torqueOnSecond.data(), 3) &&
           zero(&r.elasticEnergy, 1) && zero(r.translationalStiffness.data(), 9) &&
           zero(r.rotationalStiffnessOfFirst.data(), 9) &&
           zero(r.rotationalStiffnessOfSecond.data(), 9) && zero(&r.dashpot, 1);
}

/// What a grain–boundary slot adds to its boundary: the reaction and, for a plane, the
/// contact's stiffness along the normal and its dashpot (what a servo wall's gain is based on).
struct BoundaryReaction
{
    Vec3 force = Vec3::Zero();
    double stiffness = 0.0, dashpot = 0.0;
};

BoundaryReaction boundaryReaction(const World& w, const ContactSlot& s)
{
    BoundaryReaction reaction;
    const Boundary& b = w.boundaries[size_t(s.boundary)];
    reaction.force = s.result.forceOnSecond;
    if (b.shape == BoundaryShape::Plane) {
        // (A plane's point forces all act along its normal: the contact's dashpot is along it.)
        reaction.stiffness = b.plane.normal.dot(s.result.translationalStiffness * b.plane.normal);
        reaction.dashpot = s.result.dashpot;
    }
    return reaction;
}

void addReaction(Boundary& b, const BoundaryReaction& reaction)
{
    b.force += reaction.force;
    if (b.shape == BoundaryShape::Plane) {
        b.normalStiffness += reaction.stiffness;
        b.normalDashpot += reaction.dashpot;
    }
}

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

Simulation::Simulation(World world, double dt, bool evaluateInitialForces,
                       bool recordContactForces)
    : mWorld(std::move(world)), mDt(dt), mRecordForces(recordContactForces),
      mStabilityLimit(std::numeric_limits<double>::infinity()),
      mLargestDampingRatio(largestDampingRatio(mWorld))
{
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error("", "the time step must be a positive number", "check time_step");
    if (evaluateInitialForces) {
        evaluateForces(0.0);
        const Energies e = energies();
        mWorld.energy.initialTotal = e.kinetic + e.elastic + e.potential;
        // Grains that start in contact: a step too large for that contact would throw them
        // apart in the very first kick, before any later check could see the contact.
        checkStability(true);
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
    double workBefore = 0.0;
    for (const Boundary& b : mWorld.boundaries) workBefore -= b.force.dot(b.velocity);
    subtractPrescribedPower(workBefore);

    // Each grain moves on its own: parallel, and still the same numbers on any thread count.
    // A ghost is moved by its owner (and brought here before the forces).
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        if (!integratesGrain(i)) return;
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
    mCounters.integrateSeconds +=
        secondsSince(integrateStart) - (exchangedSeconds() - integrateExchanged);

    evaluateForces(dt);

    const auto kickStart = SteadyClock::now();
    const double kickExchanged = exchangedSeconds();
    // The second half kick and each grain's stable step limit after it, in one pass.
    mStepLimits.resize(mWorld.grains.size());
    tbb::parallel_for(size_t(0), mWorld.grains.size(), [&](size_t i) {
        Grain& g = mWorld.grains[i];
        if (g.isFree() && integratesGrain(i)) kick(g.body, g.force, g.torque, 0.5 * dt);
        mStepLimits[i] = stepLimitOf(i);
    });
    double workAfter = 0.0;
    for (const Boundary& b : mWorld.boundaries) workAfter -= b.force.dot(b.velocity);
    subtractPrescribedPower(workAfter);
    mWorld.energy.boundaryWork += 0.5 * (workBefore + workAfter) * dt;
    ++mCounters.steps;
    judgeStepLimits(mStepLimits, false);
    mCounters.integrateSeconds += secondsSince(kickStart) - (exchangedSeconds() - kickExchanged);
}

void Simulation::evaluateForces(double slipStep)
{
    World& w = mWorld;
    const auto broadStart = SteadyClock::now();
    const double broadExchanged = exchangedSeconds();
    if (mGhosts) {
        // Every rank rebuilds its list when one process would (some grain or boundary moved
        // more than half the skin), and grains change rank only then.
        // (Just distributed, the list is built anyway; a restart has stepped since, and the
        // ghosts must follow. Ghosts' own moves are their owners' to vote on.)
        const bool rebuild = mGhosts->updateGhosts(w, mContacts.needsRebuild(w));
        if (mFreshlyDistributed) {
            mContacts.markStale();
        } else if (rebuild) {
            mGhosts->redistribute(w);
            mContacts.renumber(mGhosts->renumbering());
        }
        mFreshlyDistributed = false;
    }
    const int n = static_cast<int>(w.grains.size());
    if (mContacts.update(w)) ++mCounters.listRebuilds;
    std::vector<ContactSlot>& slots = mContacts.slots();
    const size_t pairSlots = mContacts.pairSlotCount();
    // Each body as the contact laws see it (pose, velocities), in parallel.
    mViews.resize(size_t(n));
    // (Split by space, a grain's index is its global one: the contact laws break ties by it.)
    const std::vector<int>* ids = mGhosts ? &mGhosts->globalIds() : nullptr;
    tbb::parallel_for(0, n, [&](int i) {
        mViews[size_t(i)] = contactView(w.grains[size_t(i)], ids ? (*ids)[size_t(i)] : i);
    });
    mBoundaryViews.clear();
    for (const Boundary& b : w.boundaries) mBoundaryViews.push_back(contactView(b));
    mCounters.broadSeconds += secondsSince(broadStart) - (exchangedSeconds() - broadExchanged);
    mCounters.candidatePairs += static_cast<long long>(pairSlots);
    mCounters.boundaryCandidates += static_cast<long long>(slots.size() - pairSlots);

    // Narrow phase and contact laws, one slot per task; nothing shared is written.
    const auto narrowStart = SteadyClock::now();
    const bool record = mRecordForces;
    const std::vector<ContactGrain>& views = mViews;
    const std::vector<ContactGrain>& boundaryViews = mBoundaryViews;
    mSlotTotals.resize(slots.size());
    tbb::parallel_for(size_t(0), slots.size(), [&](size_t k) {
        ContactSlot& s = slots[k];
        ContactScratch& scratch = mScratch.local().value;  // this thread's buffers, reused
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
            // A level-set obstacle remembers the grain's nodes near it, as a grain pair does.
            findBoundaryContacts(*gi.asset, gi.body.pose, b, side.contacts, s.stats,
                                 &s.candidates.ofFirst);
            s.result = resolveContact(&side, 1, w.model(gi.material, b.material), slipStep, out,
                                      &scratch);
            side.contacts.swap(scratch.contacts[0]);
        }
        mSlotTotals[k] = {s.stats, s.result.elasticEnergy, s.result.contactNodes};
    });
    mCounters.narrowSeconds += secondsSince(narrowStart);

    // Sum each grain's slots in list order, grains in parallel: the same numbers whatever the
    // thread count (and the same as one pass over the slots in order).
    const auto reduceStart = SteadyClock::now();
    const double reduceExchanged = exchangedSeconds();
    mGrainStiffness.resize(size_t(n));
    tbb::parallel_for(0, n, [&](int i) {
        if (!integratesGrain(size_t(i))) return;  // a ghost's sum is its owner's
        Grain& g = w.grains[size_t(i)];
        Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
        GrainStiffness stiffness;
        for (const GrainSlotRef* r = mContacts.grainSlotsBegin(size_t(i));
             r != mContacts.grainSlotsBegin(size_t(i) + 1); ++r) {
            const ContactSlot& s = slots[size_t(r->slot)];
            const PairForces& f = s.result;
            force += r->first ? f.forceOnFirst : f.forceOnSecond;
            torque += r->first ? f.torqueOnFirst : f.torqueOnSecond;
            // The partner moves too: its share 1 + m_i/m_j (1 for a boundary or a grain that
            // forces do not move) makes the stability check a bound for every grain's
            // translation at once (stepLimitOf).
            const double partnerMass =
                s.boundary < 0 ? mViews[size_t(r->first ? s.second : s.first)].mass : 0.0;
            const double share = partnerMass > 0.0 ? 1.0 + g.body.mass / partnerMass : 1.0;
            stiffness.translation += share * f.translationalStiffness;
            stiffness.rotation +=
                share * (r->first ? f.rotationalStiffnessOfFirst : f.rotationalStiffnessOfSecond);
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
    // The slots' counts in runs of a fixed length, each run summed in order and the runs in
    // order: in parallel, and the same numbers on any thread count (whole numbers: any order).
    constexpr size_t kRun = 512;
    const size_t runs = (slots.size() + kRun - 1) / kRun;
    mRunTotals.assign(runs, SlotTotals());
    tbb::parallel_for(size_t(0), runs, [&](size_t run) {
        SlotTotals sum;
        for (size_t k = run * kRun; k < std::min(slots.size(), (run + 1) * kRun); ++k) {
            const SlotTotals& totals = mSlotTotals[k];
            sum.stats += totals.stats;
            // Split by space, a pair is counted by the owner of its first grain only.
            if (!mGhosts || k >= pairSlots || integratesGrain(size_t(slots[k].first)))
                sum.contactNodes += totals.contactNodes;
        }
        mRunTotals[run] = sum;
    });
    mContactNodes = 0;
    for (const SlotTotals& sum : mRunTotals) {
        mCounters.nodes += sum.stats;
        mContactNodes += sum.contactNodes;
    }
    // The elastic energy in one chain in list order: the order in which the ranks' terms are
    // added when the simulation is split by space (energies()), so the sums agree to the bit
    // whatever the number of contacts (runs of 512 regrouped the additions above that).
    mElastic = 0.0;
    for (size_t k = 0; k < slots.size(); ++k)
        if (!mGhosts || k >= pairSlots || integratesGrain(size_t(slots[k].first)))
            mElastic += mSlotTotals[k].elasticEnergy;
    // The boundaries' reactions, and the point forces when recorded, in slot order.
    mForces.clear();
    for (size_t k = record ? 0 : pairSlots; k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        const PairForces& r = s.result;
        if (s.boundary >= 0 && !mGhosts)
            addReaction(w.boundaries[s.boundary], boundaryReaction(w, s));
        for (size_t f = 0; f < s.forces.size(); ++f) {
            const bool onFirst = static_cast<int>(f) < r.pointForcesOnFirst;
            const int grain = onFirst ? s.first : s.second;
            if (!integratesGrain(size_t(grain))) continue;  // its owner records it
            mForces.push_back({s.forces[f].point, s.forces[f].force,
                               ids ? (*ids)[size_t(grain)] : grain});
        }
    }
    if (mGhosts) {
        sumBoundaryReactions();
        mGhosts->recordWork(mContacts);
    }
    mCounters.integrateSeconds +=
        secondsSince(reduceStart) - (exchangedSeconds() - reduceExchanged);
}

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
    const double bound = stableStepLowerBound(mGrainStiffness[i], b, mLargestDampingRatio);
    if (bound >= mDt && bound >= mStabilityLimit) return bound;
    return stableStep(mGrainStiffness[i], b, mLargestDampingRatio);
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

void Simulation::sumBoundaryReactions()
{
    const World& w = mWorld;
    const std::vector<ContactSlot>& slots = mContacts.slots();
    const std::vector<int>& ids = mGhosts->globalIds();
    std::vector<OrderedTerm> terms;
    for (size_t k = mContacts.pairSlotCount(); k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        const PairForces& r = s.result;
        if (isEmpty(r)) continue;  // adds nothing
        const BoundaryReaction reaction = boundaryReaction(w, s);
        OrderedTerm t;
        t.key[0] = ids[size_t(s.first)];
        t.key[1] = s.boundary;
        for (int c = 0; c < 3; ++c) t.value[c] = reaction.force[c];
        t.value[3] = reaction.stiffness;
        t.value[4] = reaction.dashpot;
        terms.push_back(t);
    }
    // In list order (grain, then boundary), as one process adds them.
    for (const OrderedTerm& t : mGhosts->gatherSorted(terms)) {
        BoundaryReaction reaction;
        reaction.force = Vec3(t.value[0], t.value[1], t.value[2]);
        reaction.stiffness = t.value[3];
        reaction.dashpot = t.value[4];
        addReaction(mWorld.boundaries[size_t(t.key[1])], reaction);
    }
}

void Simulation::subtractPrescribedPower(double& work)
{
    if (!mGhosts) {
        for (const Grain& g : mWorld.grains)
            if (g.motion == GrainMotion::Prescribed)
                work -= g.force.dot(g.body.velocity) + g.torque.dot(g.prescribedAngularVelocity);
        return;
    }
    if (!mHasPrescribed) return;  // the same on every rank: decided from the whole world
    const std::vector<int>& ids = mGhosts->globalIds();
    std::vector<OrderedTerm> terms;
    for (size_t i = 0; i < mWorld.grains.size(); ++i) {
        const Grain& g = mWorld.grains[i];
        if (g.motion != GrainMotion::Prescribed || !integratesGrain(i)) continue;
        OrderedTerm t;
        t.key[0] = ids[i];
        t.value[0] = g.force.dot(g.body.velocity) + g.torque.dot(g.prescribedAngularVelocity);
        terms.push_back(t);
    }
    for (const OrderedTerm& t : mGhosts->gatherSorted(terms)) work -= t.value[0];
}

long long Simulation::contactNodes() const
{
    if (!mGhosts) return mContactNodes;
    OrderedTerm mine;
    mine.key[0] = mGhosts->ranks().rank();
    mine.value[0] = static_cast<double>(mContactNodes);
    long long total = 0;
    for (const OrderedTerm& t : mGhosts->gatherSorted({mine}))
        total += static_cast<long long>(t.value[0]);
    return total;
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
    if (mGhosts) {
        // Each sum in the one-process order: grains, then the list's pairs and boundary
        // contacts (each counted by the owner of its first grain).
        const std::vector<int>& ids = mGhosts->globalIds();
        std::vector<OrderedTerm> terms;
        for (size_t i = 0; i < mWorld.grains.size(); ++i) {
            const Grain& g = mWorld.grains[i];
            if (!g.isFree() || !integratesGrain(i)) continue;
            OrderedTerm t;
            t.key[1] = ids[i];
            t.value[0] = g.body.kineticEnergy();
            t.value[1] = g.body.mass * mWorld.gravity.dot(g.body.pose.position);
            terms.push_back(t);
        }
        const std::vector<ContactSlot>& slots = mContacts.slots();
        for (size_t k = 0; k < slots.size(); ++k) {
            const ContactSlot& s = slots[k];
            const bool pair = s.boundary < 0;
            if (s.result.elasticEnergy == 0.0 || !integratesGrain(size_t(s.first))) continue;
            OrderedTerm t;
            t.key[0] = pair ? 1 : 2;
            t.key[1] = ids[size_t(s.first)];
            t.key[2] = pair ? ids[size_t(s.second)] : s.boundary;
            t.value[0] = s.result.elasticEnergy;
            terms.push_back(t);
        }
        double elastic = 0.0;
        for (const OrderedTerm& t : mGhosts->gatherSorted(terms)) {
            if (t.key[0] == 0) {
                e.kinetic += t.value[0];
                e.potential -= t.value[1];
            } else {
                elastic += t.value[0];
            }
        }
        e.elastic = elastic;
    } else {
        for (const Grain& g : mWorld.grains) {
            if (!g.isFree()) continue;
            e.kinetic += g.body.kineticEnergy();
            e.potential -= g.body.mass * mWorld.gravity.dot(g.body.pose.position);
        }
        e.elastic = mElastic;
    }
    e.boundaryWork = mWorld.energy.boundaryWork;
    e.dissipated = e.boundaryWork - (e.kinetic + e.elastic + e.potential -
                                     mWorld.energy.initialTotal);
    return e;
}

} // namespace lsdem
