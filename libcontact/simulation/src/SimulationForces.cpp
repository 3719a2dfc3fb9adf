// Simulation's force evaluation, phase by phase (Simulation.h): the MPI ghosts, the contact
// list and the bodies as the laws see them, the laws slot by slot, then the sums — each in a
// fixed order, so the numbers are the same on any thread or rank count.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/core/Stopwatch.h"
#include "lsdem/simulation/BoundaryContact.h"
#include "GlobalDamping.h"
#include "lsdem/simulation/GhostDecomposition.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

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

/// A contact's dashpot into the stability check's sums for one of its bodies (@a first: the
/// contact's first), at the partner's share @a share as its springs.
void addDashpot(GrainStiffness& sums, double share, const PairForces& f, bool first)
{
    if (!(f.dashpot > 0.0)) return;
    const double c = share * f.dashpot;
    const Vec3& arm = first ? f.dashpotArmOfFirst : f.dashpotArmOfSecond;
    // (Rank-one updates written in place: no temporary matrices, for every contact.)
    const Vec3 along = c * f.normal, turning = c * arm;
    sums.translationDamping.noalias() += along * f.normal.transpose();
    sums.rotationDamping.noalias() += turning * arm.transpose();
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
           zero(r.rotationalStiffnessOfSecond.data(), 9) && zero(&r.dashpot, 1) &&
           zero(&r.frictionWork, 1) && zero(&r.dashpotWork, 1);
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

} // namespace

void Simulation::evaluateForces(double slipStep)
{
    const auto broadStart = SteadyClock::now();
    const double broadExchanged = exchangedSeconds();
    followGhosts();
    updateContactList();
    mCounters.broadSeconds += secondsSince(broadStart) - (exchangedSeconds() - broadExchanged);

    const auto narrowStart = SteadyClock::now();
    computeContacts(slipStep);
    computeMembranes(slipStep);
    mCounters.narrowSeconds += secondsSince(narrowStart);

    const auto reduceStart = SteadyClock::now();
    const double reduceExchanged = exchangedSeconds();
    sumGrainForces(slipStep);
    sumContactCounts();
    mContactNodes += mMembraneNodes;
    mCounters.nodes += mMembraneStats;
    collectReactionsAndPointForces();
    addMembraneRimForces();
    measureCell();
    mCounters.integrateSeconds +=
        secondsSince(reduceStart) - (exchangedSeconds() - reduceExchanged);
}

void Simulation::followGhosts()
{
    if (!mGhosts) return;
    // Every rank rebuilds its list when one process would (some grain or boundary moved more
    // than half the skin), and grains change rank only then.
    // (Just distributed, the list is built anyway; a restart has stepped since, and the ghosts
    // must follow. Ghosts' own moves are their owners' to vote on.)
    const bool rebuild = mGhosts->updateGhosts(mWorld, mContacts.needsRebuild(mWorld));
    if (mFreshlyDistributed) {
        mContacts.markStale();
    } else if (rebuild) {
        mGhosts->redistribute(mWorld);
        mContacts.renumber(mGhosts->renumbering());
    }
    mFreshlyDistributed = false;
}

void Simulation::updateContactList()
{
    const World& w = mWorld;
    const int n = static_cast<int>(w.grains.size());
    if (mContacts.update(mWorld)) ++mCounters.listRebuilds;
    // Each body as the contact laws see it (pose, velocities), in parallel.
    mViews.resize(size_t(n));
    // (Split by space, a grain's index is its global one: the contact laws break ties by it.)
    const std::vector<int>* ids = mGhosts ? &mGhosts->globalIds() : nullptr;
    const bool deforming = w.periodic.deforming();
    tbb::parallel_for(0, n, [&](int i) {
        const Grain& g = w.grains[size_t(i)];
        mViews[size_t(i)] = contactView(g, ids ? (*ids)[size_t(i)] : i);
        // In a deforming periodic cell a grain moves with the cell's affine motion too.
        if (deforming && g.motion != GrainMotion::Fixed)
            mViews[size_t(i)].velocity += w.periodic.affineVelocity(g.body.pose.position);
    });
    mBoundaryViews.clear();
    for (const Boundary& b : w.boundaries) mBoundaryViews.push_back(contactView(b));
    const size_t pairSlots = mContacts.pairSlotCount();
    mCounters.candidatePairs += static_cast<long long>(pairSlots);
    mCounters.boundaryCandidates += static_cast<long long>(mContacts.slots().size() - pairSlots);
}

void Simulation::computeContacts(double slipStep)
{
    mSlotTotals.resize(mContacts.slots().size());
    (*mBackend).compute(ContactBatch{mWorld, mViews, mBoundaryViews, mContacts.slots(),
                                     mSlotTotals, slipStep, mRecordForces});
}

void Simulation::sumGrainForces(double dt)
{
    // Sum each grain's slots in list order, grains in parallel: the same numbers whatever the
    // thread count (and the same as one pass over the slots in order). A contact's dissipation
    // goes to its first grain, summed in the same order.
    World& w = mWorld;
    const std::vector<ContactSlot>& slots = mContacts.slots();
    const int n = static_cast<int>(w.grains.size());
    mGrainStiffness.resize(size_t(n));
    tbb::parallel_for(0, n, [&](int i) {
        if (!integratesGrain(size_t(i))) return;  // a ghost's sum is its owner's
        Grain& g = w.grains[size_t(i)];
        Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
        GrainStiffness stiffness;
        double friction = 0.0, dashpot = 0.0;
        for (const GrainSlotRef* r = mContacts.grainSlotsBegin(size_t(i));
             r != mContacts.grainSlotsBegin(size_t(i) + 1); ++r) {
            const ContactSlot& s = slots[size_t(r->slot)];
            const PairForces& f = s.result;
            // A slot without contact nodes holds resolveContact's empty result: every term
            // below is +0, which changes no sum (they start at +0). Most slots of a packing.
            if (f.contactNodes == 0) continue;
            force += r->first ? f.forceOnFirst : f.forceOnSecond;
            torque += r->first ? f.torqueOnFirst : f.torqueOnSecond;
            if (r->first) {  // each contact's dissipation counts once, with its first grain
                friction += f.frictionWork;
                dashpot += f.dashpotWork;
            }
            // The partner moves too: its share 1 + m_i/m_j (1 for a boundary or a grain that
            // forces do not move) makes the stability check a bound for every grain's
            // translation at once (stepLimitOf).
            const double partnerMass =
                s.boundary < 0 ? mViews[size_t(r->first ? s.second : s.first)].mass : 0.0;
            const double share = partnerMass > 0.0 ? 1.0 + g.body.mass / partnerMass : 1.0;
            stiffness.translation += share * f.translationalStiffness;
            stiffness.rotation +=
                share * (r->first ? f.rotationalStiffnessOfFirst : f.rotationalStiffnessOfSecond);
            addDashpot(stiffness, share, f, r->first);
        }
        // The membranes press on it as walls do, but for the stability check with the share
        // of the pair that the membrane's motion leaves it (MembraneGrainContact; the
        // vertices' part is in the membrane's check).
        for (const std::vector<MembraneGrainContact>& onMembrane : mMembraneContacts) {
            const MembraneGrainContact& c = onMembrane[size_t(i)];
            const PairForces& f = c.result;
            force += f.forceOnFirst;
            torque += f.torqueOnFirst;
            dashpot += f.dashpotWork;
            stiffness.translation += c.grainShare * f.translationalStiffness;
            stiffness.rotation += c.grainShare * f.rotationalStiffnessOfFirst;
            addDashpot(stiffness, c.grainShare, f, true);
        }
        if (g.isFree()) {
            force += g.body.mass * w.gravity;
            if (w.globalDamping > 0.0) {
                g.dissipated.globalDamping +=
                    dampedWork(force, g.body.velocity, w.globalDamping, dt) +
                    dampedWork(torque, g.body.angularVelocity(), w.globalDamping, dt);
                force = dampComponents(force, g.body.velocity, w.globalDamping);
                torque = dampComponents(torque, g.body.angularVelocity(), w.globalDamping);
            }
        }
        g.dissipated.friction += friction;
        g.dissipated.dashpot += dashpot;
        g.force = force;
        g.torque = torque;
        mGrainStiffness[size_t(i)] = stiffness;
    });
}

void Simulation::sumContactCounts()
{
    const std::vector<ContactSlot>& slots = mContacts.slots();
    const size_t pairSlots = mContacts.pairSlotCount();
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
}

void Simulation::collectReactionsAndPointForces()
{
    World& w = mWorld;
    const std::vector<ContactSlot>& slots = mContacts.slots();
    const std::vector<int>* ids = mGhosts ? &mGhosts->globalIds() : nullptr;
    for (Boundary& b : w.boundaries) b.force = Vec3::Zero(), b.normalStiffness = b.normalDashpot = 0.0;
    // The boundaries' reactions, and the point forces when recorded, in slot order.
    mForces.clear();
    for (size_t k = mRecordForces ? 0 : mContacts.pairSlotCount(); k < slots.size(); ++k) {
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

} // namespace lsdem
