// What a run reads from a Simulation besides its state: energies, nodes and contacts counted,
// and the power of prescribed grains — summed, split by space, in the one-process order.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/simulation/GhostDecomposition.h"

namespace lsdem {

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

void Simulation::measureCell()
{
    PeriodicCell& cell = mWorld.periodic;
    if (!cell.deforming()) return;
    // The contacts against the affine motion: a pair's first grain feels f while its partner's
    // image moves away at ε̇ ∘ (branch vector); a grain on a boundary moves at the affine
    // velocity of its place. And the Love–Weber moment of the same contacts along each axis.
    // In list order (the same sums on any thread count).
    // Split by space, each contact's terms come from the rank owning its first grain, and are
    // added in the one-process order: pairs by their grains' global indices, then boundary
    // contacts by grain and boundary (key[2]: twice the boundary, +1 for the Love–Weber part).
    Vec3 moment = Vec3::Zero(), loveWeber = Vec3::Zero();
    std::vector<OrderedTerm> terms;
    const auto keep = [&](long long kind, long long first, long long second, const Vec3& term) {
        OrderedTerm t;
        t.key[0] = kind;
        t.key[1] = first;
        t.key[2] = second;
        for (int c = 0; c < 3; ++c) t.value[c] = term[c];
        terms.push_back(t);
    };
    const std::vector<int>* ids = mGhosts ? &mGhosts->globalIds() : nullptr;
    const std::vector<ContactSlot>& slots = mContacts.slots();
    for (size_t k = 0; k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        if (s.result.contactNodes <= 0 || !integratesGrain(size_t(s.first))) continue;
        const Vec3& f = s.result.forceOnFirst;
        const Vec3& first = mWorld.grains[size_t(s.first)].body.pose.position;
        if (s.boundary < 0) {
            const Vec3 branch = mWorld.grains[size_t(s.second)].body.pose.position +
                                cell.imageShift(s.periods) - first;
            const Vec3 term = branch.cwiseProduct(f);
            if (ids) {
                keep(0, (*ids)[size_t(s.first)], (*ids)[size_t(s.second)], term);
                continue;
            }
            moment += term;
            loveWeber += term;
        } else {
            const Vec3 pull = -(first - cell.origin).cwiseProduct(f);
            const Vec3 lever = (s.result.centre - first).cwiseProduct(f);
            if (ids) {
                keep(1, (*ids)[size_t(s.first)], 2LL * s.boundary, pull);
                keep(1, (*ids)[size_t(s.first)], 2LL * s.boundary + 1, lever);
                continue;
            }
            moment += pull;
            loveWeber += lever;
        }
    }
    if (mGhosts)
        for (const OrderedTerm& t : mGhosts->gatherSorted(terms)) {
            const Vec3 term(t.value[0], t.value[1], t.value[2]);
            if (t.key[0] == 0) {
                moment += term;
                loveWeber += term;
            } else if (t.key[2] % 2 == 0) {
                moment += term;
            } else {
                loveWeber += term;
            }
        }
    mWorld.energy.cellMoment = moment;
    // (A stress needs the sample's volume: a cell periodic along all three axes.)
    cell.stress = cell.volume() > 0.0 ? Vec3(-loveWeber / cell.volume()) : Vec3::Zero();
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

std::vector<ContactRecord> Simulation::contactRecords() const
{
    std::vector<ContactRecord> records;
    const std::vector<ContactSlot>& slots = mContacts.slots();
    for (size_t k = 0; k < slots.size(); ++k) {
        const ContactSlot& s = slots[k];
        if (s.result.contactNodes <= 0) continue;
        ContactRecord r;
        r.first = s.first;
        if (k < mContacts.pairSlotCount()) {
            r.second = s.second;
            r.shift = mWorld.periodic.imageShift(s.periods);
        } else
            r.boundary = s.boundary;
        r.force = s.result.forceOnFirst;
        r.centre = s.result.centre;
        r.normal = s.result.normal;
        r.nodes = s.result.contactNodes;
        records.push_back(r);
    }
    // Then each grain's contact with each membrane (its nodes against the triangles), so the
    // grains' equilibrium, and the Love–Weber stress made of it, counts the membrane's push.
    for (size_t k = 0; k < mMembraneContacts.size(); ++k)
        for (size_t i = 0; i < mMembraneContacts[k].size(); ++i) {
            const PairForces& c = mMembraneContacts[k][i].result;
            if (c.contactNodes <= 0) continue;
            ContactRecord r;
            r.first = static_cast<int>(i);
            r.membrane = static_cast<int>(k);
            r.force = c.forceOnFirst;
            r.centre = c.centre;
            r.normal = c.normal;
            r.nodes = c.contactNodes;
            for (const PointForce& f : mMembraneContacts[k][i].pointForces)
                r.spread += (f.point - r.centre) * f.force.transpose();
            records.push_back(r);
        }
    return records;
}

Energies Simulation::energies() const
{
    Energies e;
    if (mGhosts) {
        // Each sum in the one-process order: grains, then the list's pairs and boundary
        // contacts (each counted by the owner of its first grain).
        const std::vector<int>& ids = mGhosts->globalIds();
        std::vector<OrderedTerm> terms;
        // (Every grain for its dissipation, a free one for its energies too: key[2] says which.)
        for (size_t i = 0; i < mWorld.grains.size(); ++i) {
            const Grain& g = mWorld.grains[i];
            if (!integratesGrain(i)) continue;
            OrderedTerm t;
            t.key[1] = ids[i];
            t.key[2] = g.isFree() ? 1 : 0;
            if (g.isFree()) {
                t.value[0] = g.body.kineticEnergy();
                t.value[1] = g.body.mass * mWorld.gravity.dot(g.unwrappedPosition());
            }
            t.value[2] = g.dissipated.friction;
            t.value[3] = g.dissipated.dashpot;
            t.value[4] = g.dissipated.globalDamping;
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
                if (t.key[2] == 1) {
                    e.kinetic += t.value[0];
                    e.potential -= t.value[1];
                }
                e.friction += t.value[2];
                e.dashpot += t.value[3];
                e.globalDamping += t.value[4];
            } else {
                elastic += t.value[0];
            }
        }
        e.elastic = elastic;
    } else {
        for (const Grain& g : mWorld.grains) {
            if (g.isFree()) {
                e.kinetic += g.body.kineticEnergy();
                e.potential -= g.body.mass * mWorld.gravity.dot(g.unwrappedPosition());
            }
            e.friction += g.dissipated.friction;
            e.dashpot += g.dissipated.dashpot;
            e.globalDamping += g.dissipated.globalDamping;
        }
        e.elastic = mElastic;
    }
    double membraneKinetic = 0.0;
    e.elastic += membraneEnergy(membraneKinetic);
    e.kinetic += membraneKinetic;
    for (const Membrane& m : mWorld.membranes) e.globalDamping += m.dampedWork;
    e.boundaryWork = mWorld.energy.boundaryWork;
    e.dissipated = e.boundaryWork - (e.kinetic + e.elastic + e.potential -
                                     mWorld.energy.initialTotal);
    return e;
}

} // namespace lsdem
