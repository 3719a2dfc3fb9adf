#include "lsdem/contact/ContactLaw.h"

#include <algorithm>
#include <array>
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

/// The unit direction of point force @a f of a side: its contact's normal for a per-node law
/// (@a contact not null), else the force's own direction (zero for a zero force).
Vec3 directionOf(const PointForce& f, const NodeContact* contact)
{
    if (contact) return contact->normal;
    const double size = f.force.norm();
    return size > 0.0 ? Vec3(f.force / size) : Vec3::Zero();
}

/// The contact seen as one body of springs: where it acts, along which normal, how stiff it is
/// along it and how fast its force grows with penetration. What its dashpot is made from.
struct ContactAxis
{
    Vec3 centre = Vec3::Zero();  ///< stiffness-weighted centre of the point forces
    Vec3 normal = Vec3::Zero();  ///< unit, pushing first out of second (zero: none)
    double stiffness = 0.0;      ///< Σ k_f·(n_f·n)²: the stiffness along the normal
    double force = 0.0;          ///< P: the elastic force along the normal (on first)
    double exponent = 1.0;       ///< d ln P / d ln δ ≈ δ_max·K/P (1 for a flat face)
};

/// The axis of the elastic point forces @a forces[s] of the @a sideCount sides. @a summed: the
/// law sums the nodes (every law but the single-node one, whose force is one node's spring).
ContactAxis contactAxis(const ContactSide* sides, int sideCount,
                        const std::vector<PointForce>* forces, bool perNodeForces, bool summed)
{
    ContactAxis axis;
    const ContactGrain* first = sides[0].tester;
    double total = 0.0, deepest = 0.0, area = 0.0, areaSquares = 0.0;
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
        for (const NodeContact& c : sides[s].contacts) {
            deepest = std::max(deepest, c.depth);
            area += c.area;
            areaSquares += c.area * c.area;
        }
    }
    const double normalLength = weightedNormal.norm();
    if (!(total > 0.0) || !(normalLength > 0.0)) return axis;
    axis.centre = weightedPoint / total;
    axis.normal = weightedNormal / normalLength;
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
        const double nodes = summed && areaSquares > 0.0 ? area * area / areaSquares : 0.0;
        const double overlap = nodes > 0.0 ? deepest * (1.0 + 1.0 / nodes) : deepest;
        axis.exponent = std::max(1.0, overlap * axis.stiffness / force);
    }
    return axis;
}

/// The contact's stiffness for the stability check (PairForces, SimulationForces.cpp), summed point
/// force by point force: the lower triangles of k'·n nᵀ and, per movable body, of k'·w wᵀ and
/// −k_t·r rᵀ (k' = k_n − k_t, w = r × n), with Σ k_t and Σ k_t·|r|² for the diagonal terms
/// added at the end. Written out in plain numbers: it runs for every node in contact.
class StiffnessSum
{
public:
    StiffnessSum(const ContactGrain& first, const ContactGrain& second)
        : mFirstCentre(first.pose.position), mSecondCentre(second.pose.position),
          mFirstMoves(first.mass > 0.0), mSecondMoves(second.mass > 0.0)
    {
    }

    void add(double normalStiffness, double shearStiffness, const Vec3& n, const Vec3& point)
    {
        const double k = normalStiffness - shearStiffness;
        const double nx = n.x(), ny = n.y(), nz = n.z();
        addLower(mTranslation, k * nx, k * ny, k * nz, nx, ny, nz);
        mShear += shearStiffness;
        if (mFirstMoves) addLever(mFirst, k, shearStiffness, nx, ny, nz, point, mFirstCentre);
        if (mSecondMoves) addLever(mSecond, k, shearStiffness, nx, ny, nz, point, mSecondCentre);
    }

    void store(PairForces& result) const
    {
        result.translationalStiffness = full(mTranslation, mShear);
        if (mFirstMoves) result.rotationalStiffnessOfFirst = full(mFirst.lower, mFirst.diagonal);
        if (mSecondMoves)
            result.rotationalStiffnessOfSecond = full(mSecond.lower, mSecond.diagonal);
    }

private:
    /// Lower triangle xx, yx, zx, yy, zy, zz.
    using Lower = std::array<double, 6>;
    struct Rotation
    {
        Lower lower{};
        double diagonal = 0.0;
    };

    /// m += (ax, ay, az)·(bx, by, bz)ᵀ, the lower triangle.
    static void addLower(Lower& m, double ax, double ay, double az, double bx, double by,
                         double bz)
    {
        m[0] += ax * bx;
        m[1] += ay * bx;
        m[2] += az * bx;
        m[3] += ay * by;
        m[4] += az * by;
        m[5] += az * bz;
    }
    static void addLever(Rotation& m, double k, double shear, double nx, double ny, double nz,
                         const Vec3& point, const Vec3& centre)
    {
        const double rx = point.x() - centre.x(), ry = point.y() - centre.y(),
                     rz = point.z() - centre.z();
        const double wx = ry * nz - rz * ny, wy = rz * nx - rx * nz, wz = rx * ny - ry * nx;
        addLower(m.lower, k * wx, k * wy, k * wz, wx, wy, wz);
        if (shear > 0.0) {
            addLower(m.lower, -shear * rx, -shear * ry, -shear * rz, rx, ry, rz);
            m.diagonal += shear * (rx * rx + ry * ry + rz * rz);
        }
    }
    static Mat3 full(const Lower& m, double diagonal)
    {
        Mat3 out;
        out << m[0] + diagonal, m[1], m[2], m[1], m[3] + diagonal, m[4], m[2], m[4],
            m[5] + diagonal;
        return out;
    }

    Vec3 mFirstCentre, mSecondCentre;
    bool mFirstMoves, mSecondMoves;
    Lower mTranslation{};
    double mShear = 0.0;
    Rotation mFirst, mSecond;
};

/// The contact's dashpot (DampingModel.h): one force on first at the contact's centre along its
/// normal, against the approach (second gets the opposite), and its share per unit of point
/// force stiffness, which counts as normal force in Coulomb's limit.
struct Dashpot
{
    double coefficient = 0.0;          ///< c (0: none)
    ContactAxis axis;
    Vec3 force = Vec3::Zero();         ///< on first
    double viscousPerStiffness = 0.0;  ///< its normal force over Σ k of the point forces
};

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
    double total = 0.0;
    for (int s = 0; s < sideCount; ++s)
        for (const PointForce& f : normal[s]) total += f.stiffness;
    d.viscousPerStiffness = viscous / total;
    return d;
}

/// The stored shear of each node of a side, found by walking the sorted history alongside the
/// nodes (in node order; from the start again if a caller gave them otherwise).
class StoredShear
{
public:
    explicit StoredShear(const ShearHistory* history)
        : mStored(history ? &history->entries() : nullptr)
    {
    }
    Vec3 of(int node)
    {
        if (node < mLastNode) {
            mInOrder = false;
            mCursor = 0;
        }
        mLastNode = node;
        while (mCursor < mStored->size() && (*mStored)[mCursor].node < node) ++mCursor;
        return mCursor < mStored->size() && (*mStored)[mCursor].node == node
                   ? (*mStored)[mCursor].force
                   : Vec3::Zero();
    }
    /// Whether the nodes came in order (else the new history needs sorting).
    bool inOrder() const { return mInOrder; }

private:
    const std::vector<ShearHistory::Entry>* mStored;
    size_t mCursor = 0;
    int mLastNode = -1;
    bool mInOrder = true;
};

/// Side @a side's point forces @a forces (on its tester) added to the pair's forces and
/// torques: on the tester, and the opposite on the other body.
void addSideForces(const ContactSide& side, const ContactGrain& first,
                   const std::vector<PointForce>& forces, PairForces& result)
{
    const bool testerIsFirst = side.tester == &first;
    Vec3& forceOnTester = testerIsFirst ? result.forceOnFirst : result.forceOnSecond;
    Vec3& torqueOnTester = testerIsFirst ? result.torqueOnFirst : result.torqueOnSecond;
    Vec3& forceOnOther = testerIsFirst ? result.forceOnSecond : result.forceOnFirst;
    Vec3& torqueOnOther = testerIsFirst ? result.torqueOnSecond : result.torqueOnFirst;
    // Sums in locals (registers), not in `result`, which the compiler must assume the stores
    // to the point forces may alias; the additions happen in the same order.
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
}

} // namespace

PairForces resolveContact(ContactSide* sides, int sideCount, const ContactModel& model,
                          double dt, std::vector<PointForce>* allForces, ContactScratch* scratch)
{
    ContactScratch temporary;
    ContactScratch& work = scratch ? *scratch : temporary;
    PairForces result;
    const ContactGrain& first = *sides[0].tester;
    const ContactGrain& second = *sides[0].other;

    // The normal laws first, for every side: the dashpot is the whole contact's.
    const NormalModel& normalLaw = model.normal();
    const ShearSpringModel shearSprings = model.tangential();
    std::vector<PointForce>* normal = work.forces;
    for (int s = 0; s < sideCount; ++s) {
        normal[s].clear();
        normalLaw.forces(sides[s].contacts, model.normalStiffness, sides[s].weight, normal[s]);
        result.contactNodes += static_cast<int>(sides[s].contacts.size());
    }
    const bool perNodeShear = shearSprings.active(normalLaw);
    // A per-node law gives contact i exactly one force, k_i·d_i along its unit normal n_i
    // (NormalModel::perNodeForces): its size and direction are read from the contact rather
    // than recovered from the force with a root and divisions.
    const bool perNodeForces = normalLaw.perNodeForces();
    const bool shearPerArea = normalLaw.stiffnessPerArea();
    for (int s = 0; s < sideCount; ++s)
        if (perNodeForces && normal[s].size() != sides[s].contacts.size())
            throw std::logic_error("resolveContact: a per-node normal law gave " +
                                   std::to_string(normal[s].size()) + " forces for " +
                                   std::to_string(sides[s].contacts.size()) + " contacts");

    const Dashpot dashpot = contactDashpot(sides, sideCount, model, normal, perNodeForces);
    result.dashpot = dashpot.coefficient;
    // The turn of the shear history about the normal in this step: the pair's mean spin.
    const Vec3 meanTurn = (0.5 * dt) * (first.angularVelocity + second.angularVelocity);

    // Shear springs, elastic energy and stiffness, point force by point force; sums in locals
    // (registers), as in addSideForces.
    double elasticEnergy = 0.0;
    StiffnessSum stiffness(first, second);
    for (int s = 0; s < sideCount; ++s) {
        ContactSide& side = sides[s];
        std::vector<PointForce>& forces = normal[s];
        std::vector<ShearHistory::Entry>& nextHistory = work.nextHistory;
        nextHistory.clear();
        StoredShear stored(side.history);
        for (size_t k = 0; k < forces.size(); ++k) {
            PointForce& f = forces[k];
            const NodeContact* c = perNodeForces ? &side.contacts[k] : nullptr;
            const double size = c ? f.stiffness * c->depth : f.force.norm();
            if (size == 0.0 || f.stiffness <= 0.0) continue;
            const Vec3 n = c ? c->normal : Vec3(f.force / size);
            // ½·(k·d)·d for a per-node force; the other laws' energy is added once per side.
            if (c) elasticEnergy += 0.5 * size * c->depth;
            double shearStiffness = 0.0;
            if (perNodeShear && side.history) {
                // (perNodeShear implies a per-node law, so c is this force's contact.) Nodes
                // that left contact lose their history; nodes that entered start from zero.
                // Coulomb's limit is μ times the node's normal force: its spring and its share
                // of the dashpot (which the bodies feel as normal force too).
                shearStiffness = shearSprings.nodeStiffness(shearPerArea, c->area, side.weight);
                const Vec3 relativeVelocity =
                    side.tester->pointVelocity(f.point) - side.other->pointVelocity(f.point);
                const Vec3 shear = updateShearForce(
                    stored.of(c->node), c->normal, relativeVelocity * dt, meanTurn.dot(n),
                    shearStiffness,
                    shearSprings.friction *
                        std::max(0.0, size + dashpot.viscousPerStiffness * f.stiffness));
                nextHistory.push_back({c->node, shear});
                f.force += shear;
                elasticEnergy += 0.5 * shear.squaredNorm() / shearStiffness;
            }
            stiffness.add(f.stiffness, shearStiffness, n, f.point);
        }
        if (!perNodeForces && !forces.empty())
            elasticEnergy += normalLaw.elasticEnergy(side.contacts, model.normalStiffness,
                                                     side.weight);
        if (side.history) {
            if (!stored.inOrder())
                std::sort(nextHistory.begin(), nextHistory.end(),
                          [](const auto& a, const auto& b) { return a.node < b.node; });
            side.history->replaceWith(nextHistory);
        }

        addSideForces(side, first, forces, result);
        if (allForces) allForces->insert(allForces->end(), forces.begin(), forces.end());
        if (s == 0 && result.dashpot > 0.0) {
            if (allForces) allForces->push_back({-1, dashpot.force, dashpot.axis.centre, 0.0});
            ++result.pointForcesOnFirst;
        }
    }
    if (result.dashpot > 0.0) {
        result.forceOnFirst += dashpot.force;
        accumulateMoment(result.torqueOnFirst, dashpot.axis.centre, Point3(first.pose.position),
                         dashpot.force, false);
        result.forceOnSecond -= dashpot.force;
        accumulateMoment(result.torqueOnSecond, dashpot.axis.centre, Point3(second.pose.position),
                         dashpot.force, true);
    }
    result.elasticEnergy = elasticEnergy;
    stiffness.store(result);
    return result;
}

} // namespace lsdem
