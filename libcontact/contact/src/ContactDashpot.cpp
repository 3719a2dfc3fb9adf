// The contact's dashpot (ContactDashpot.h).
#include "ContactDashpot.h"

#include "ForceSums.h"

#include <algorithm>
#include <cmath>

namespace lsdem::contactlaw {

namespace {

/// The mass that the contact's dashpot acts on: the reduced mass of two free bodies, or the
/// free one's mass against an immovable one (0 when neither can move).
double effectiveMass(const ContactGrain& a, const ContactGrain& b)
{
    if (a.mass > 0.0 && b.mass > 0.0) return a.mass * b.mass / (a.mass + b.mass);
    return std::max(a.mass, b.mass);
}

} // namespace

ContactPlace contactPlace(const ContactSide* sides, int sideCount,
                          const std::vector<PointForce>* forces, bool perNodeForces)
{
    ContactPlace place;
    const ContactGrain* first = sides[0].tester;
    double total = 0.0;
    Vec3 weightedPoint = Vec3::Zero(), weightedNormal = Vec3::Zero();
    for (int s = 0; s < sideCount; ++s) {
        const double sign = sides[s].tester == first ? 1.0 : -1.0;
        for (size_t k = 0; k < forces[s].size(); ++k) {
            const PointForce& f = forces[s][k];
            const NodeContact* c = perNodeForces ? &sides[s].contacts[k] : nullptr;
            total += f.stiffness;
            weightedPoint += f.stiffness * f.point;
            weightedNormal += (sign * f.stiffness) * directionOf(f, c);
        }
    }
    const double normalLength = weightedNormal.norm();
    if (!(total > 0.0) || !(normalLength > 0.0)) return place;
    place.centre = weightedPoint / total;
    place.normal = weightedNormal / normalLength;
    return place;
}

namespace {

/// The axis of the elastic point forces @a forces[s] of the @a sideCount sides. @a summed: the
/// law sums the nodes (every law but the single-node one, whose force is one node's spring).
ContactAxis contactAxis(const ContactSide* sides, int sideCount,
                        const std::vector<PointForce>* forces, bool perNodeForces, bool summed)
{
    ContactAxis axis;
    const ContactPlace place = contactPlace(sides, sideCount, forces, perNodeForces);
    if (place.normal.isZero(0.0)) return axis;
    axis.centre = place.centre;
    axis.normal = place.normal;
    const ContactGrain* first = sides[0].tester;
    double deepest = 0.0, area = 0.0, areaSquares = 0.0;
    bool patches = false;
    for (int s = 0; s < sideCount; ++s)
        for (const NodeContact& c : sides[s].contacts) {
            deepest = std::max(deepest, c.deepest());
            area += c.area;
            areaSquares += c.area * c.area;
            patches |= c.isPatch();
        }
    // Along the normal: the stiffness K, and the elastic force P that it builds up.
    double& force = axis.force;
    for (int s = 0; s < sideCount; ++s) {
        const double sign = sides[s].tester == first ? 1.0 : -1.0;
        for (size_t k = 0; k < forces[s].size(); ++k) {
            const PointForce& f = forces[s][k];
            const double along = directionOf(f, perNodeForces ? &sides[s].contacts[k] : nullptr)
                                     .dot(axis.normal);
            axis.stiffness += f.stiffness * along * along;
            force += sign * f.force.dot(axis.normal);
        }
    }
    // P = κ·δ^p gives p = δ·K/P, δ the contact's overlap. The deepest node stands for it; on
    // a curved contact, whose nodes' depths spread evenly over [0, δ] (a cap's area grows in
    // proportion to depth), the deepest of n nodes is δ·n/(n + 1) deep on average, so the
    // overlap is δ_max·(1 + 1/n), n the nodes' effective count (Σ A)²/Σ A². (A flat face's
    // nodes all sit at one depth, but there n is large.) Without that, a contact of a few nodes
    // would look flat, p → 1, and get a linear spring's damping. Every node is at most δ_max
    // deep, so P ≤ δ_max·K: p ≥ 1.
    if (force > 0.0) {
        // Patches know their deepest point (to second order): that is the overlap itself.
        const double nodes =
            summed && !patches && areaSquares > 0.0 ? area * area / areaSquares : 0.0;
        const double overlap = nodes > 0.0 ? deepest * (1.0 + 1.0 / nodes) : deepest;
        axis.exponent = std::max(1.0, overlap * axis.stiffness / force);
    }
    return axis;
}

} // namespace

Dashpot contactDashpot(const ContactSide* sides, int sideCount, const ContactModel& model,
                       const std::vector<PointForce>* normal, bool perNodeForces)
{
    Dashpot d;
    if (!model.damping.active()) return d;
    const ContactGrain& first = *sides[0].tester;
    const ContactGrain& second = *sides[0].other;
    d.axis = contactAxis(sides, sideCount, normal, perNodeForces,
                         perNodeForces || model.normal().stiffnessPerArea());
    d.coefficient =
        model.damping.dashpot(effectiveMass(first, second), d.axis.stiffness, d.axis.exponent);
    if (!(d.coefficient > 0.0)) return d;
    const Vec3 relative = first.pointVelocity(d.axis.centre) - second.pointVelocity(d.axis.centre);
    // It may push but not pull: at most the elastic force, against it, as the bodies part
    // (DampingModel.h).
    const double viscous =
        std::max(-d.coefficient * relative.dot(d.axis.normal), -std::max(d.axis.force, 0.0));
    d.force = viscous * d.axis.normal;
    d.power = -viscous * relative.dot(d.axis.normal);  // viscous opposes the normal rate: ≥ 0
    // Each point force's friction limit counts a share of it as normal force, in proportion to
    // the force's own size (the size the shear springs read). So no share turns a limit
    // negative (viscous ≥ −P ≥ −Σ|F|), and the limits add up to μ times springs and dashpot
    // together. (Shared per unit stiffness, a pull cut the shallow nodes' limits at zero while
    // the deep ones kept theirs: more than μ·N in all.)
    double total = 0.0;
    for (int s = 0; s < sideCount; ++s)
        for (size_t k = 0; k < normal[s].size(); ++k)
            total += normalForceSize(normal[s][k], perNodeForces ? &sides[s].contacts[k] : nullptr);
    if (total > 0.0) d.viscousPerForce = viscous / total;
    return d;
}

} // namespace lsdem::contactlaw
