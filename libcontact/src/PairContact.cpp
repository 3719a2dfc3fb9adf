#include "lsdem/contact/PairContact.h"

#include "lsdem/contact/ShearSpring.h"

#include <cmath>

namespace lsdem {

namespace {

bool hasPerNodeShear(const ContactModel& model)
{
    return (model.formulation == Formulation::Original ||
            model.formulation == Formulation::Adapted) &&
           model.friction > 0.0 && model.shearStiffness > 0.0;
}

/// Velocity of the material point of @a g at world point @a p.
Vec3 pointVelocity(const ContactGrain& g, const Vec3& p)
{
    return g.velocity + g.angularVelocity.cross(p - g.pose.position);
}

/// Nodes of @a tester inside @a other: forces on @a tester (and the opposite on @a other).
void testOneDirection(const ContactGrain& tester, const ContactGrain& other,
                      const ContactModel& model, double weight, double dt,
                      std::map<int, Vec3>* history, NodeCheckStats& stats, Vec3& forceOnTester,
                      Vec3& torqueOnTester, Vec3& forceOnOther, Vec3& torqueOnOther,
                      int& contactNodes, std::vector<PointForce>* allForces)
{
    std::vector<NodeContact> contacts;
    findNodeContacts(*tester.asset, tester.pose, *other.asset, other.pose, contacts, stats);
    contactNodes += static_cast<int>(contacts.size());
    std::vector<PointForce> forces;
    normalForces(model.formulation, contacts, model.normalStiffness, weight, forces);

    if (history && hasPerNodeShear(model)) {
        // Per-node laws give forces[k] for contacts[k]. Nodes that left contact lose their
        // history; nodes that entered start from zero.
        std::map<int, Vec3> next;
        for (size_t k = 0; k < contacts.size(); ++k) {
            const NodeContact& c = contacts[k];
            const auto found = history->find(c.node);
            const Vec3 stored = found == history->end() ? Vec3::Zero() : found->second;
            const Vec3 slip = (pointVelocity(tester, c.point) - pointVelocity(other, c.point)) * dt;
            const double stiffness = weight * model.shearStiffness *
                                     (model.formulation == Formulation::Adapted ? c.area : 1.0);
            const Vec3 shear = updateShearForce(stored, c.normal, slip, stiffness,
                                                model.friction * forces[k].force.norm());
            next.emplace(c.node, shear);
            forces[k].force += shear;
        }
        history->swap(next);
    } else if (history) {
        history->clear();
    }

    for (const PointForce& f : forces) {
        forceOnTester += f.force;
        torqueOnTester += (f.point - tester.pose.position).cross(f.force);
        forceOnOther -= f.force;
        torqueOnOther -= (f.point - other.pose.position).cross(f.force);
    }
    if (allForces) allForces->insert(allForces->end(), forces.begin(), forces.end());
}

} // namespace

PairForces computePairContact(const ContactGrain& first, const ContactGrain& second,
                              const ContactModel& model, double dt, PairHistory* history,
                              NodeCheckStats& stats, std::vector<PointForce>* forces)
{
    PairForces result;
    std::map<int, Vec3>* firstHistory = history ? &history->shearOnFirstNodes : nullptr;
    std::map<int, Vec3>* secondHistory = history ? &history->shearOnSecondNodes : nullptr;
    bool testFirst = true, testSecond = true;
    double weight = 0.5;
    if (model.testing == NodeTesting::OneWay) {
        // The smaller grain's nodes; on a tie (within round-off), the lower index's.
        const double ra = first.asset->boundingRadius, rb = second.asset->boundingRadius;
        const bool tie = std::abs(ra - rb) <= 1e-9 * std::max(ra, rb);
        testFirst = tie ? first.index <= second.index : ra < rb;
        testSecond = !testFirst;
        weight = 1.0;
    }
    if (testFirst)
        testOneDirection(first, second, model, weight, dt, firstHistory, stats,
                         result.forceOnFirst, result.torqueOnFirst, result.forceOnSecond,
                         result.torqueOnSecond, result.contactNodes, forces);
    else if (firstHistory)
        firstHistory->clear();
    if (testSecond)
        testOneDirection(second, first, model, weight, dt, secondHistory, stats,
                         result.forceOnSecond, result.torqueOnSecond, result.forceOnFirst,
                         result.torqueOnFirst, result.contactNodes, forces);
    else if (secondHistory)
        secondHistory->clear();
    return result;
}

} // namespace lsdem
