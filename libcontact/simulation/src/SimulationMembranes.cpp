// Simulation's membranes (Membrane.h): their vertices stepped by velocity Verlet beside the
// grains, their forces (stretching, pressure, the grains' contacts) at each evaluation, and
// what they add to the energy balance and the stability check. Each grain's contact with a
// membrane is computed in parallel and handed to the vertices in grain order, so the numbers
// are the same on any thread count.
#include "lsdem/simulation/Simulation.h"

#include "lsdem/core/Error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <sstream>

namespace lsdem {

namespace {

/// Velocity of vertex @a i of @a m: its own, or its holder's.
Vec3 vertexVelocity(const Membrane& m, size_t i, const std::vector<Boundary>& boundaries)
{
    return m.heldBy[i] >= 0 ? boundaries[size_t(m.heldBy[i])].velocity : m.velocities[i];
}

/// What acts on vertex @a i from outside the grains and the membrane's own rubber: the
/// pressure's share on a free vertex; on a held one, also what its holder must add to keep it
/// on its course (the opposite of every other force on it).
Vec3 externalForce(const Membrane& m, size_t i, const Vec3& pressure)
{
    return m.heldBy[i] >= 0 ? Vec3(pressure - m.forces[i]) : pressure;
}

} // namespace

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
        for (size_t i = 0; i < m.positions.size(); ++i)
            power += externalForce(m, i, mMembranePressureForces[k][i])
                         .dot(vertexVelocity(m, i, mWorld.boundaries));
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
    mMembranePressureForces.resize(membranes);
    mMembraneContactStiffness.resize(membranes);
    mMembraneElastic = 0.0;
    mMembraneNodes = 0;
    mMembraneStats = NodeCheckStats();
    for (size_t k = 0; k < membranes; ++k) {
        Membrane& m = w.membranes[k];
        // The rubber and the pressure; the pressure's part kept for the work it does.
        computeMembraneForces(m, &mMembranePressureForces[k]);

        // The grains' contacts, grain by grain in parallel.
        MembraneTriangleGrid& grid = mMembraneGrids[k];
        grid.build(m, m.contactReach);
        std::vector<MembraneGrainContact>& contacts = mMembraneContacts[k];
        contacts.resize(w.grains.size());
        std::vector<NodeCheckStats> stats(w.grains.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, w.grains.size()),
                          [&](const tbb::blocked_range<size_t>& range) {
                              ContactScratch scratch;
                              for (size_t i = range.begin(); i != range.end(); ++i)
                                  computeMembraneContact(mViews[i], m, grid,
                                                         w.model(w.grains[i].material, m.material),
                                                         dt, contacts[i], stats[i], scratch);
                          });
        // Their reactions on the vertices, in grain order.
        std::vector<double>& stiffness = mMembraneContactStiffness[k];
        stiffness.assign(m.positions.size(), 0.0);
        for (size_t i = 0; i < w.grains.size(); ++i) {
            mMembraneStats += stats[i];
            mMembraneNodes += contacts[i].result.contactNodes;
            mMembraneElastic += contacts[i].result.elasticEnergy;
            for (const auto& [vertex, force] : contacts[i].reactions) m.forces[size_t(vertex)] += force;
            for (const auto& [vertex, kv] : contacts[i].stiffness) stiffness[size_t(vertex)] += kv;
        }
        // Numerical damping as the grains have it (World::globalDamping), on free vertices.
        if (w.globalDamping > 0.0)
            for (size_t i = 0; i < m.positions.size(); ++i) {
                if (m.heldBy[i] >= 0) continue;
                Vec3& f = m.forces[i];
                for (int c = 0; c < 3; ++c) {
                    const double along = f[c] * m.velocities[i][c];
                    const double sign = along > 0.0 ? 1.0 : along < 0.0 ? -1.0 : 0.0;
                    m.dampedWork += w.globalDamping * std::abs(along) * dt;
                    f[c] *= 1.0 - w.globalDamping * sign;
                }
            }
    }
}

double Simulation::membraneStepLimit(std::string* which) const
{
    double limit = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < mWorld.membranes.size(); ++k) {
        const Membrane& m = mWorld.membranes[k];
        // The rubber's bound, and each free vertex on the grains' contacts as on springs.
        double omegaSquared = m.rubberOmegaSquared;
        double contact = 0.0;
        if (k < mMembraneContactStiffness.size())
            for (size_t i = 0; i < m.positions.size(); ++i)
                if (m.heldBy[i] < 0)
                    contact = std::max(contact, mMembraneContactStiffness[k][i] / m.masses[i]);
        omegaSquared += contact;
        const double step = omegaSquared > 0.0 ? 2.0 / std::sqrt(omegaSquared)
                                               : std::numeric_limits<double>::infinity();
        if (step < limit) {
            limit = step;
            if (which) *which = m.name;
        }
    }
    return limit;
}

void Simulation::judgeMembraneStep() const
{
    std::string which;
    const double limit = membraneStepLimit(&which);
    if (!(mDt > limit)) return;
    std::ostringstream problem;
    problem << "the time step " << mDt << " exceeds the stability limit " << limit
            << " of membrane '" << which << "' (its rubber and the grains pressing on it)";
    throw Error("", problem.str(),
                "give a smaller time_step, or a larger membrane density (mass scaling)");
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
