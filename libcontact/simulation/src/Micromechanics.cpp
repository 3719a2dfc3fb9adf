#include "lsdem/simulation/Micromechanics.h"

#include <cmath>

namespace lsdem {

namespace {

/// Whether grain @a index of @a world belongs to the sample (a free grain).
bool inSample(const World& world, int index)
{
    return index >= 0 && world.grains[size_t(index)].isFree();
}

/// Calls @a act(grain, moment) for each free grain that contact @a r acts on, with the
/// contact's moment about that grain's position (second's image across a periodic cell's face):
/// (centre − x) ⊗ r.force and r.spread on the first grain, the opposite forces at the same
/// points on the second.
template <typename Act>
void forEachSampleGrain(const World& world, const ContactRecord& r, Act&& act)
{
    if (inSample(world, r.first)) {
        const Vec3& x = world.grains[size_t(r.first)].body.pose.position;
        act(r.first, Mat3((r.centre - x) * r.force.transpose() + r.spread));
    }
    if (inSample(world, r.second)) {
        const Vec3 x = world.grains[size_t(r.second)].body.pose.position + r.shift;
        act(r.second, Mat3(-(r.centre - x) * r.force.transpose() - r.spread));
    }
}

/// sqrt(3/2·a:a) of a = 15/2·(@a fabric − I/3): 0 for an isotropic fabric.
double anisotropyOf(const Mat3& fabric)
{
    const Mat3 a = 7.5 * (fabric - Mat3::Identity() / 3.0);
    return std::sqrt(1.5 * (a.array() * a.array()).sum());
}

} // namespace

Micromechanics micromechanicsOf(const World& world, const std::vector<ContactRecord>& records)
{
    Micromechanics m;
    std::vector<int> contacts(world.grains.size(), 0);
    for (const ContactRecord& r : records) {
        forEachSampleGrain(world, r, [&](int, const Mat3& moment) { m.stressMoment += moment; });
        if (inSample(world, r.first) && inSample(world, r.second)) {
            ++m.grainContacts;
            ++contacts[size_t(r.first)];
            ++contacts[size_t(r.second)];
            m.fabric += r.normal * r.normal.transpose();
            const Vec3 branch = world.grains[size_t(r.second)].body.pose.position + r.shift -
                                world.grains[size_t(r.first)].body.pose.position;
            if (branch.squaredNorm() > 0.0)
                m.branchFabric += branch * branch.transpose() / branch.squaredNorm();
            const double normalForce = std::abs(r.force.dot(r.normal));
            m.forceFabric += normalForce * r.normal * r.normal.transpose();
            m.meanNormalForce += normalForce;
        } else if (inSample(world, r.first) || inSample(world, r.second)) {
            ++m.boundaryContacts;
        }
    }
    int none = 0, one = 0;
    for (size_t p = 0; p < world.grains.size(); ++p) {
        if (!world.grains[p].isFree()) continue;
        ++m.freeGrains;
        none += contacts[p] == 0;
        one += contacts[p] == 1;
    }
    m.rattlers = none + one;
    if (m.freeGrains > m.rattlers)
        m.mechanicalCoordination =
            double(2 * m.grainContacts - one) / double(m.freeGrains - m.rattlers);
    if (m.grainContacts > 0) {
        m.fabric /= double(m.grainContacts);
        m.fabricAnisotropy = anisotropyOf(m.fabric);
        m.branchFabric /= double(m.grainContacts);
        m.branchAnisotropy = anisotropyOf(m.branchFabric);
        if (m.meanNormalForce > 0.0) {
            m.forceFabric /= m.meanNormalForce;
            m.forceAnisotropy = anisotropyOf(m.forceFabric);
        }
        m.meanNormalForce /= double(m.grainContacts);
    }
    return m;
}

std::vector<Mat3> grainStresses(const World& world, const std::vector<ContactRecord>& records)
{
    std::vector<Mat3> stress(world.grains.size(), Mat3::Zero());
    for (const ContactRecord& r : records)
        forEachSampleGrain(world, r, [&](int p, const Mat3& moment) { stress[size_t(p)] += moment; });
    for (size_t p = 0; p < world.grains.size(); ++p) {
        const Grain& g = world.grains[p];
        if (g.isFree()) stress[p] /= g.asset->mass.volume;
    }
    return stress;
}

} // namespace lsdem
