#include "lsdem/contact/ContactLaw.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lsdem {

namespace {

/// The mass that the contact's dashpot acts on: the reduced mass of two free bodies, or the
/// free one's mass against an immovable one (0 when neither can move).
double effectiveMass(const ContactGrain& a, const ContactGrain& b)
{
    if (a.mass > 0.0 && b.mass > 0.0) return a.mass * b.mass / (a.mass + b.mass);
    return std::max(a.mass, b.mass);
}

/// A point as three numbers. A Vec3 copied into a local may be stored in a 16- and an 8-byte
/// piece and then read back across both, which stalls until the stores complete.
struct Point3
{
    double x, y, z;
    explicit Point3(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
};

/// @a sum += (p − c) × f, or −= with @a subtract; component by component, the same operations
/// as Eigen's cross product, which would go through memory and stall the sum reading it back.
void accumulateMoment(Vec3& sum, const Vec3& p, const Point3& c, const Vec3& f, bool subtract)
{
    const double rx = p.x() - c.x, ry = p.y() - c.y, rz = p.z() - c.z;
    const double mx = ry * f.z() - rz * f.y(), my = rz * f.x() - rx * f.z(),
                 mz = rx * f.y() - ry * f.x();
    if (subtract)
        sum = Vec3(sum.x() - mx, sum.y() - my, sum.z() - mz);
    else
        sum = Vec3(sum.x() + mx, sum.y() + my, sum.z() + mz);
}

} // namespace

PairForces resolveContact(ContactSide* sides, int sideCount, const ContactModel& model,
                          double dt, std::vector<PointForce>* allForces, ContactScratch* scratch)
{
    ContactScratch temporary;
    ContactScratch& work = scratch ? *scratch : temporary;
    PairForces result;
    const ContactGrain* first = sides[0].tester;

    // The normal laws first, for every side, so that the dashpot sees the whole contact's
    // stiffness K (both directions of symmetric testing together).
    const NormalModel& normalLaw = model.normal();
    const ShearSpringModel shearSprings = model.tangential();
    std::vector<PointForce>* normal = work.forces;
    double totalStiffness = 0.0;
    for (int s = 0; s < sideCount; ++s) {
        normal[s].clear();
        normalLaw.forces(sides[s].contacts, model.normalStiffness, sides[s].weight, normal[s]);
        for (const PointForce& f : normal[s]) totalStiffness += f.stiffness;
        result.contactNodes += static_cast<int>(sides[s].contacts.size());
    }
    // c_f = 2β·sqrt(m/K)·k_f: the dashpots add up to 2β·sqrt(m·K), shared by stiffness.
    const double dashpotPerStiffness = model.damping().dashpotPerStiffness(
        effectiveMass(*sides[0].tester, *sides[0].other), totalStiffness);
    const bool perNodeShear = shearSprings.active(normalLaw);
    // A per-node law gives contact i exactly one force, k_i·d_i along its unit normal n_i
    // (NormalModel::perNodeForces): its size and direction are read from the contact rather
    // than recovered from the force with a root and divisions.
    const bool perNodeForces = normalLaw.perNodeForces();
    const bool shearPerArea = normalLaw.stiffnessPerArea();

    // Sums kept in locals (registers), not in `result`, which the compiler must assume the
    // stores to the point forces may alias; the additions happen in the same order.
    double elasticEnergy = result.elasticEnergy;
    Mat3 normalStiffness = result.normalStiffness;
    for (int s = 0; s < sideCount; ++s) {
        ContactSide& side = sides[s];
        std::vector<PointForce>& forces = normal[s];
        std::vector<ShearHistory::Entry>& nextHistory = work.nextHistory;
        nextHistory.clear();
        // The stored shear of each node, found by walking the sorted history alongside the
        // nodes (in node order; a binary search if a caller gave them otherwise).
        const std::vector<ShearHistory::Entry>* stored =
            side.history ? &side.history->entries() : nullptr;
        size_t cursor = 0;
        int lastNode = -1;
        bool inOrder = true;
        auto storedShear = [&](int node) -> Vec3 {
            if (node < lastNode) {
                inOrder = false;
                cursor = 0;
            }
            lastNode = node;
            while (cursor < stored->size() && (*stored)[cursor].node < node) ++cursor;
            return cursor < stored->size() && (*stored)[cursor].node == node
                       ? (*stored)[cursor].force
                       : Vec3::Zero();
        };
        if (perNodeForces && forces.size() != side.contacts.size())
            throw std::logic_error("resolveContact: a per-node normal law gave " +
                                   std::to_string(forces.size()) + " forces for " +
                                   std::to_string(side.contacts.size()) + " contacts");
        for (size_t k = 0; k < forces.size(); ++k) {
            PointForce& f = forces[k];
            const NodeContact* c = perNodeForces ? &side.contacts[k] : nullptr;
            const double size = c ? f.stiffness * c->depth : f.force.norm();
            if (size == 0.0 || f.stiffness <= 0.0) continue;
            const Vec3 n = c ? c->normal : Vec3(f.force / size);
            // ½·(k·d)·d for a per-node force; the other laws' energy is added once per side.
            if (c) elasticEnergy += 0.5 * size * c->depth;
            // += k·n·nᵀ, entry by entry (the same products as Eigen's expression, which goes
            // through a temporary matrix in memory and stalls reading it back).
            const Vec3 kn = f.stiffness * n;
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row) normalStiffness(row, col) += kn[row] * n[col];
            const Vec3 relativeVelocity =
                side.tester->pointVelocity(f.point) - side.other->pointVelocity(f.point);
            Vec3 total = f.force;
            if (dashpotPerStiffness > 0.0)
                total -= (dashpotPerStiffness * f.stiffness * relativeVelocity.dot(n)) * n;
            if (perNodeShear && side.history) {
                // (perNodeShear implies a per-node law, so c is this force's contact.) Nodes
                // that left contact lose their history; nodes that entered start from zero.
                const double shearStiffness =
                    shearSprings.nodeStiffness(shearPerArea, c->area, side.weight);
                const Vec3 shear = updateShearForce(storedShear(c->node), c->normal,
                                                    relativeVelocity * dt, shearStiffness,
                                                    shearSprings.friction * size);
                nextHistory.push_back({c->node, shear});
                total += shear;
                elasticEnergy += 0.5 * shear.squaredNorm() / shearStiffness;
            }
            f.force = total;
        }
        if (!perNodeForces && !forces.empty())
            elasticEnergy += normalLaw.elasticEnergy(side.contacts, model.normalStiffness,
                                                     side.weight);
        if (side.history) {
            if (!inOrder)
                std::sort(nextHistory.begin(), nextHistory.end(),
                          [](const auto& a, const auto& b) { return a.node < b.node; });
            side.history->replaceWith(nextHistory);
        }

        const bool testerIsFirst = side.tester == first;
        Vec3& forceOnTester = testerIsFirst ? result.forceOnFirst : result.forceOnSecond;
        Vec3& torqueOnTester = testerIsFirst ? result.torqueOnFirst : result.torqueOnSecond;
        Vec3& forceOnOther = testerIsFirst ? result.forceOnSecond : result.forceOnFirst;
        Vec3& torqueOnOther = testerIsFirst ? result.torqueOnSecond : result.torqueOnFirst;
        Vec3 testerForce = forceOnTester, testerTorque = torqueOnTester;
        Vec3 otherForce = forceOnOther, otherTorque = torqueOnOther;
        const Point3 testerCentre(side.tester->pose.position), otherCentre(side.other->pose.position);
        for (const PointForce& f : forces) {
            testerForce += f.force;
            accumulateMoment(testerTorque, f.point, testerCentre, f.force, false);
            otherForce -= f.force;
            accumulateMoment(otherTorque, f.point, otherCentre, f.force, true);
        }
        forceOnTester = testerForce;
        torqueOnTester = testerTorque;
        forceOnOther = otherForce;
        torqueOnOther = otherTorque;
        if (testerIsFirst) result.pointForcesOnFirst += static_cast<int>(forces.size());
        if (allForces) allForces->insert(allForces->end(), forces.begin(), forces.end());
    }
    result.elasticEnergy = elasticEnergy;
    result.normalStiffness = normalStiffness;
    return result;
}

} // namespace lsdem
