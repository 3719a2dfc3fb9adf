// Simulation's membranes (Membrane.h): their vertices stepped by velocity Verlet beside the
// grains, their forces (stretching, pressure, the grains' contacts) at each evaluation, and
// what they add to the energy balance and the stability check. Each grain's contact with a
// membrane is computed in parallel and handed to the vertices in grain order, so the numbers
// are the same on any thread count.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/StableStep.h"

#include "lsdem/core/Error.h"

#include "GlobalDamping.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <sstream>

namespace lsdem {

void Simulation::checkMembranes() const
{
    for (const Membrane& m : mWorld.membranes) {
        const std::string where = "membrane '" + m.name + "'";
        if (m.material < 0 || m.material >= mWorld.materialCount)
            throw Error(where, "its contact material is not one of the world's");
        if (m.masses.size() != m.positions.size() || m.heldBy.size() != m.positions.size())
            throw Error(where, "it was not finished", "call finishMembrane after making it");
        for (const int b : m.heldBy)
            if (b >= static_cast<int>(mWorld.boundaries.size()))
                throw Error(where, "a vertex is held by a boundary the world does not have");
    }
}

double Simulation::membraneExternalPower() const
{
    double power = 0.0;
    for (size_t k = 0; k < mWorld.membranes.size(); ++k) {
        const Membrane& m = mWorld.membranes[k];
        if (m.pressureForces.size() != m.positions.size()) continue;  // (none evaluated yet)
        for (size_t i = 0; i < m.positions.size(); ++i)
            // (A held vertex moves at its holder's velocity, set as it moved; the holder is a
            // boundary, whose work counts its pull.)
            power += m.pressureForces[i].dot(m.velocities[i]);
    }
    return power;
}

void Simulation::moveMembranes(double dt)
{
    for (Membrane& m : mWorld.membranes)
        for (size_t i = 0; i < m.positions.size(); ++i) {
            if (m.heldBy[i] >= 0) {
                m.velocities[i] = mWorld.boundaries[size_t(m.heldBy[i])].velocity;
            } else {
                m.velocities[i] += 0.5 * dt / m.masses[i] * m.forces[i];
            }
            m.positions[i] += dt * m.velocities[i];
        }
}

void Simulation::kickMembranes(double halfStep)
{
    for (Membrane& m : mWorld.membranes)
        for (size_t i = 0; i < m.positions.size(); ++i)
            if (m.heldBy[i] < 0) m.velocities[i] += halfStep / m.masses[i] * m.forces[i];
}

void Simulation::computeMembranes(double dt)
{
    World& w = mWorld;
    const size_t membranes = w.membranes.size();
    mMembraneContacts.resize(membranes);
    mMembraneGrids.resize(membranes);
    mMembraneContactStiffness.resize(membranes);
    mMembraneContactDamping.resize(membranes);
    mMembraneElastic = 0.0;
    mMembraneNodes = 0;
    mMembraneStats = NodeCheckStats();
    for (size_t k = 0; k < membranes; ++k) {
        Membrane& m = w.membranes[k];
        // The rubber and the pressure; the pressure's part kept for the work it does.
        computeMembraneForces(m, &m.pressureForces);

        // The grains' contacts, grain by grain in parallel (split by space, each by its
        // owner: every rank holds the whole membrane, and a ghost's contact is its owner's).
        MembraneTriangleGrid& grid = mMembraneGrids[k];
        grid.update(m, m.contactReach);
        std::vector<MembraneGrainContact>& contacts = mMembraneContacts[k];
        contacts.resize(w.grains.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, w.grains.size()),
                          [&](const tbb::blocked_range<size_t>& range) {
                              ContactScratch scratch;
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  if (!integratesGrain(i)) {
                                      contacts[i] = MembraneGrainContact();
                                      continue;
                                  }
                                  computeMembraneContact(mViews[i], m, grid,
                                                         w.model(w.grains[i].material, m.material),
                                                         dt, contacts[i], scratch);
                              }
                          });
        for (const MembraneGrainContact& c : contacts) {
            mMembraneStats += c.stats;
            mMembraneNodes += c.result.contactNodes;  // (this rank's: contactNodes() sums them)
        }
        addGrainReactions(k);
        // The cell fluid's drag.
        if (m.drag > 0.0)
            for (size_t i = 0; i < m.positions.size(); ++i) {
                if (m.heldBy[i] >= 0) continue;
                const double area = m.masses[i] / (m.rubber.density * m.rubber.thickness);
                const Vec3 drag = -m.drag * area * m.velocities[i];
                m.forces[i] += drag;
                m.dampedWork -= drag.dot(m.velocities[i]) * dt;
            }
        // Numerical damping as the grains have it (World::globalDamping), on free vertices.
        if (w.globalDamping > 0.0)
            for (size_t i = 0; i < m.positions.size(); ++i) {
                if (m.heldBy[i] >= 0) continue;
                m.dampedWork += dampedWork(m.forces[i], m.velocities[i], w.globalDamping, dt);
                m.forces[i] = dampComponents(m.forces[i], m.velocities[i], w.globalDamping);
            }
    }
}

void Simulation::addGrainReactions(size_t k)
{
    // The grains' reactions on the vertices, in grain order (and each grain's in its order):
    // split by space, gathered from the grains' owners and added in that order on every rank,
    // so every rank moves the whole membrane alike.
    Membrane& m = mWorld.membranes[k];
    const std::vector<MembraneGrainContact>& contacts = mMembraneContacts[k];
    std::vector<double>& stiffness = mMembraneContactStiffness[k];
    std::vector<double>& damping = mMembraneContactDamping[k];
    stiffness.assign(m.positions.size(), 0.0);
    damping.assign(m.positions.size(), 0.0);
    m.grainForces.assign(m.positions.size(), Vec3::Zero());
    const auto push = [&](int vertex, const Vec3& force) {
        m.forces[size_t(vertex)] += force;
        m.grainForces[size_t(vertex)] += force;
    };
    if (!mGhosts) {
        for (const MembraneGrainContact& c : contacts) {
            mMembraneElastic += c.result.elasticEnergy;
            for (const auto& [vertex, force] : c.reactions) push(vertex, force);
            for (const MembraneVertexLoad& l : c.loads) {
                stiffness[size_t(l.vertex)] += l.stiffness;
                damping[size_t(l.vertex)] += l.damping;
            }
        }
        return;
    }
    // key: global grain, then 0 its elastic energy, 1 a reaction, 2 a vertex's load; then its
    // place.
    const std::vector<int>& ids = mGhosts->globalIds();
    std::vector<OrderedTerm> terms;
    for (size_t i = 0; i < contacts.size(); ++i) {
        const MembraneGrainContact& c = contacts[i];
        if (c.reactions.empty() && c.loads.empty() && c.result.elasticEnergy == 0.0) continue;
        OrderedTerm t;
        t.key[0] = ids[i];
        t.value[0] = c.result.elasticEnergy;
        terms.push_back(t);
        t.key[1] = 1;
        for (size_t r = 0; r < c.reactions.size(); ++r) {
            t.key[2] = static_cast<long long>(r);
            t.value[0] = c.reactions[r].first;
            for (int a = 0; a < 3; ++a) t.value[1 + a] = c.reactions[r].second[a];
            terms.push_back(t);
        }
        t.key[1] = 2;
        for (size_t r = 0; r < c.loads.size(); ++r) {
            t.key[2] = static_cast<long long>(r);
            t.value[0] = c.loads[r].vertex;
            t.value[1] = c.loads[r].stiffness;
            t.value[2] = c.loads[r].damping;
            terms.push_back(t);
        }
    }
    for (const OrderedTerm& t : mGhosts->gatherSorted(terms)) {
        const int vertex = static_cast<int>(t.value[0]);
        if (t.key[1] == 0)
            mMembraneElastic += t.value[0];
        else if (t.key[1] == 1)
            push(vertex, Vec3(t.value[1], t.value[2], t.value[3]));
        else {
            stiffness[size_t(vertex)] += t.value[1];
            damping[size_t(vertex)] += t.value[2];
        }
    }
}

void Simulation::addMembraneRimForces()
{
    for (const Membrane& m : mWorld.membranes)
        for (size_t i = 0; i < m.positions.size(); ++i)
            if (m.heldBy[i] >= 0) mWorld.boundaries[size_t(m.heldBy[i])].force += m.forces[i];
}

double Simulation::membraneStepLimit(std::string* which) const
{
    double limit = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < mWorld.membranes.size(); ++k) {
        const Membrane& m = mWorld.membranes[k];
        const MembraneStepParts parts = membraneStepParts(k);
        // (Global damping strengthens the vertices' forces against their motion, as the grains'.)
        const double step = dampedStableStep(parts.rubber + parts.contacts,
                                             membraneDragRate(m) + parts.contactDamping,
                                             mWorld.globalDamping);
        if (step < limit) {
            limit = step;
            if (which) {
                std::ostringstream text;
                text << "membrane '" << m.name << "' (ω² of its rubber " << parts.rubber
                     << " /s², of the grains pressing on its vertices " << parts.contacts
                     << " /s², its drag's rate " << membraneDragRate(m)
                     << " /s, the grains' dashpots' on a vertex " << parts.contactDamping
                     << " /s)";
                *which = text.str();
            }
        }
    }
    return limit;
}

Simulation::MembraneStepParts Simulation::membraneStepParts(size_t k) const
{
    // The rubber's bound, and each free vertex on the grains' contacts as on springs and
    // dashpots of its own (its share of each pair: MembraneGrainContact). The three add up:
    // the largest eigenvalue of a sum is at most the sum of theirs, and the contacts' are
    // diagonal.
    const Membrane& m = mWorld.membranes[k];
    MembraneStepParts parts;
    parts.rubber = m.rubberOmegaSquared;
    if (k < mMembraneContactStiffness.size())
        for (size_t i = 0; i < m.positions.size(); ++i)
            if (m.heldBy[i] < 0) {
                parts.contacts = std::max(parts.contacts, mMembraneContactStiffness[k][i] / m.masses[i]);
                parts.contactDamping =
                    std::max(parts.contactDamping, mMembraneContactDamping[k][i] / m.masses[i]);
            }
    return parts;
}

void Simulation::judgeMembraneStep() const
{
    std::string which;
    const double limit = membraneStepLimit(&which);
    if (!(mDt > limit)) return;
    std::ostringstream problem;
    problem << "the time step " << mDt << " exceeds the stability limit " << limit << " of "
            << which;
    throw Error("", problem.str(),
                "give a smaller time_step, a larger membrane density (mass scaling) or less drag");
}

void Simulation::judgeMembraneForecast() const
{
    for (size_t k = 0; k < mWorld.membranes.size() && k < mMembraneContactStiffness.size(); ++k) {
        const Membrane& m = mWorld.membranes[k];
        // Pressed now: some free vertex bears a contact (summed over every rank's grains, so
        // every rank judges alike).
        bool pressed = false;
        for (size_t i = 0; i < m.positions.size(); ++i)
            pressed |= m.heldBy[i] < 0 && mMembraneContactStiffness[k][i] > 0.0;
        if (!pressed) continue;
        const double limit = stiffestMembraneContactStep(mWorld, m, m.rubberOmegaSquared);
        if (!(mDt > 2.0 * limit)) continue;
        std::ostringstream problem, fix;
        problem << "the time step " << mDt << " exceeds the stability limit " << limit
                << " of the stiffest contact a grain can make on membrane '" << m.name
                << "' (a face pressed over a vertex's triangles), which grains press at the start:"
                   " the run would explode";
        fix << "set [simulation] time_step to at most " << 0.2 * limit
            << " (a fifth of the limit), or use \"auto\"; or raise the membrane's density (mass "
               "scaling)";
        throw Error("", problem.str(), fix.str());
    }
}

double Simulation::membraneEnergy(double& kinetic) const
{
    double elastic = mMembraneElastic;
    kinetic = 0.0;
    for (const Membrane& m : mWorld.membranes) {
        elastic += m.strainEnergy;
        kinetic += membraneKineticEnergy(m);
    }
    return elastic;
}

} // namespace lsdem
