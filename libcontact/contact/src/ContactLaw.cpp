#include "lsdem/contact/ContactLaw.h"

#include "ContactDashpot.h"
#include "ForceSums.h"
#include "SideLaneSums.h"
#include "lsdem/contact/ShearSpringLanes.h"
#include "lsdem/contact/TangentialModel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lsdem {

namespace {

using namespace contactlaw;

/// The contact's stiffness for the stability check (PairForces, SimulationForces.cpp), summed point
/// force by point force (or a side's sums made elsewhere added whole, addSide): the lower triangles of k'·n nᵀ and, per movable body, of k'·w wᵀ and
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

    /// A side's sums already made (SideLaneSums), whose tester is the first body if
    /// @a testerIsFirst.
    void addSide(const SideTotals& t, bool testerIsFirst)
    {
        addTo(mTranslation, t.translation);
        mShear += t.shear;
        Rotation& tester = testerIsFirst ? mFirst : mSecond;
        Rotation& other = testerIsFirst ? mSecond : mFirst;
        if (testerIsFirst ? mFirstMoves : mSecondMoves) {
            addTo(tester.lower, t.testerLower);
            tester.diagonal += t.testerDiagonal;
        }
        if (testerIsFirst ? mSecondMoves : mFirstMoves) {
            addTo(other.lower, t.otherLower);
            other.diagonal += t.otherDiagonal;
        }
    }

    void store(PairForces& result) const
    {
        result.translationalStiffness = full(mTranslation, mShear);
        if (mFirstMoves) result.rotationalStiffnessOfFirst = full(mFirst.lower, mFirst.diagonal);
        if (mSecondMoves)
            result.rotationalStiffnessOfSecond = full(mSecond.lower, mSecond.diagonal);
    }

private:
    using Lower = LowerTriangle;
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
    static void addTo(Lower& m, const Lower& add)
    {
        for (size_t i = 0; i < m.size(); ++i) m[i] += add[i];
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

/// The stored shear of each node of a side, found by walking the sorted history alongside the
/// nodes (in node order; from the start again if a caller gave them otherwise).
class StoredShear
{
public:
    explicit StoredShear(const ShearHistory* history)
        : mStored(history ? &history->entries() : nullptr)
    {
    }
    /// @a node's entry (zero force and stiffness for a node just entering contact).
    ShearHistory::Entry of(int node)
    {
        if (node < mLastNode) {
            mInOrder = false;
            mCursor = 0;
        }
        mLastNode = node;
        while (mCursor < mStored->size() && (*mStored)[mCursor].node < node) ++mCursor;
        return mCursor < mStored->size() && (*mStored)[mCursor].node == node
                   ? (*mStored)[mCursor]
                   : ShearHistory::Entry{node, Vec3::Zero(), 0.0};
    }
    /// Whether the nodes came in order (else the new history needs sorting).
    bool inOrder() const { return mInOrder; }

private:
    const std::vector<ShearHistory::Entry>* mStored;
    size_t mCursor = 0;
    int mLastNode = -1;
    bool mInOrder = true;
};

/// The pair's forces and torques as a side sees them: on its tester and on the other body.
struct SideResult
{
    bool testerIsFirst;
    Vec3& forceOnTester;
    Vec3& torqueOnTester;
    Vec3& forceOnOther;
    Vec3& torqueOnOther;

    static SideResult of(const ContactSide& side, const ContactGrain& first, PairForces& result)
    {
        const bool testerIsFirst = side.tester == &first;
        return {testerIsFirst,
                testerIsFirst ? result.forceOnFirst : result.forceOnSecond,
                testerIsFirst ? result.torqueOnFirst : result.torqueOnSecond,
                testerIsFirst ? result.forceOnSecond : result.forceOnFirst,
                testerIsFirst ? result.torqueOnSecond : result.torqueOnFirst};
    }
};

/// Side @a side's point forces @a forces (on its tester) added to the pair's forces and
/// torques: on the tester, and the opposite on the other body.
void addSideForces(const ContactSide& side, const ContactGrain& first,
                   const std::vector<PointForce>& forces, PairForces& result)
{
    const SideResult on = SideResult::of(side, first, result);
    // Sums in locals (registers), not in `result`, which the compiler must assume the stores
    // to the point forces may alias; the additions happen in the same order.
    Vec3 testerForce = on.forceOnTester, testerTorque = on.torqueOnTester;
    Vec3 otherForce = on.forceOnOther, otherTorque = on.torqueOnOther;
    const Point3 testerCentre(side.tester->pose.position), otherCentre(side.other->pose.position);
    for (const PointForce& f : forces) {
        testerForce += f.force;
        accumulateMoment(testerTorque, f.point, testerCentre, f.force, false);
        otherForce -= f.force;
        accumulateMoment(otherTorque, f.point, otherCentre, f.force, true);
    }
    on.forceOnTester = testerForce;
    on.torqueOnTester = testerTorque;
    on.forceOnOther = otherForce;
    on.torqueOnOther = otherTorque;
    if (on.testerIsFirst) result.pointForcesOnFirst += static_cast<int>(forces.size());
}

/// Side @a side's force and moments already summed (@a t, SideLaneSums) added to the pair's,
/// as addSideForces adds them; @a count is the side's number of point forces.
void addSideTotals(const ContactSide& side, const ContactGrain& first, const SideTotals& t,
                   size_t count, PairForces& result)
{
    const SideResult on = SideResult::of(side, first, result);
    on.forceOnTester += t.forceOnTester;
    on.torqueOnTester += t.torqueOnTester;
    on.forceOnOther -= t.forceOnTester;
    on.torqueOnOther += t.torqueOnOther;
    if (on.testerIsFirst) result.pointForcesOnFirst += static_cast<int>(count);
}

/// The normal law's point forces of every side into @a normal[s]; the number of contact nodes.
/// A per-node law must give one force per contact (NormalModel::perNodeForces).
int normalForces(const ContactSide* sides, int sideCount, const ContactModel& model,
                 std::vector<PointForce>* normal)
{
    const NormalModel& law = model.normal();
    int nodes = 0;
    for (int s = 0; s < sideCount; ++s) {
        normal[s].clear();
        law.forces(sides[s].contacts, model.normalStiffness, sides[s].weight, normal[s]);
        nodes += static_cast<int>(sides[s].contacts.size());
        if (law.perNodeForces() && normal[s].size() != sides[s].contacts.size())
            throw std::logic_error("resolveContact: a per-node normal law gave " +
                                   std::to_string(normal[s].size()) + " forces for " +
                                   std::to_string(sides[s].contacts.size()) + " contacts");
    }
    return nodes;
}

/// The contact's dashpot force on both bodies, at its axis's centre.
void addDashpot(const Dashpot& dashpot, const ContactGrain& first, const ContactGrain& second,
                PairForces& result)
{
    result.forceOnFirst += dashpot.force;
    accumulateMoment(result.torqueOnFirst, dashpot.axis.centre, Point3(first.pose.position),
                     dashpot.force, false);
    result.forceOnSecond -= dashpot.force;
    accumulateMoment(result.torqueOnSecond, dashpot.axis.centre, Point3(second.pose.position),
                     dashpot.force, true);
}

/// Where the contact acts and along which normal: the dashpot's axis if it has one, else the
/// place its point forces give.
void placeContact(const ContactSide* sides, int sideCount, const std::vector<PointForce>* normal,
                  bool perNodeForces, const Dashpot& dashpot, PairForces& result)
{
    if (dashpot.axis.normal.isZero(0.0)) {
        const ContactPlace place = contactPlace(sides, sideCount, normal, perNodeForces);
        result.centre = place.centre;
        result.normal = place.normal;
    } else {
        result.centre = dashpot.axis.centre;
        result.normal = dashpot.axis.normal;
    }
}

/// What the pass over each side's point forces needs of the whole contact, fixed before the
/// first side: one bundle rather than eight arguments to every helper below.
struct SidePass
{
    const ContactModel& model;
    ShearSpringModel shearSprings;
    /// A per-node law gives contact i exactly one force, k_i·d_i along its unit normal n_i
    /// (NormalModel::perNodeForces): its size and direction are read from the contact rather
    /// than recovered from the force with a root and divisions.
    bool perNodeForces;
    bool perNodeShear;  ///< shear springs at the nodes (implies perNodeForces)
    bool shearPerArea;  ///< their stiffness is per unit area
    double viscousPerForce;  ///< the dashpot's normal force over Σ|F_n| (Dashpot)
    Vec3 meanTurn;  ///< the shear history's turn about the normal in this step
    double dt;
};

/// A stored spring carried into a step where its stiffness is @a stiffness. Only patch
/// quadrature's springs change stiffness (ks*·A_in, the patch's area in contact): the shear
/// traction stays, so a spring whose area shrank lets go of the force the lost area carried,
/// F·k/k_old (kept whole, its energy ½F²/k would grow without work), and one whose area grew
/// keeps its force (the new area starts unloaded, as Mindlin's annulus). Friction's work is the
/// work of the force the bodies felt, less the spring's energy gained (updateShearForce): the
/// energy ½F²/k the change took, and, as the bodies felt the force before it was let go of over
/// this step's slip, half the let-go force's work along it.
struct CarriedSpring
{
    Vec3 force;              ///< the stored force as this step's spring holds it
    bool changed = false;    ///< the stiffness changed: friction's work gains @a released
    double released = 0.0;   ///< ½(F_old²/k_old − F²/k)
    bool shrank = false;     ///< the stiffness fell: friction's work loses @a letGoWork
    double letGoWork = 0.0;  ///< ½(F_old − F)·slip

    /// Both terms added to @a frictionWork, in the order the step's arithmetic has them.
    void addWork(double& frictionWork) const
    {
        if (changed) frictionWork += released;
        if (shrank) frictionWork -= letGoWork;
    }
};

/// @a previous, whose spring's stiffness changed, carried into a step of stiffness @a stiffness
/// and slip @a slip (CarriedSpring). Out of line: only patch quadrature's springs come here.
CarriedSpring carryChangedSpring(const ShearHistory::Entry& previous, double stiffness,
                                 const Vec3& slip)
{
    CarriedSpring carried{previous.force};
    carried.changed = true;
    carried.shrank = stiffness < previous.stiffness;
    if (carried.shrank) carried.force = previous.force * (stiffness / previous.stiffness);
    carried.released = 0.5 * (previous.force.squaredNorm() / previous.stiffness -
                              carried.force.squaredNorm() / stiffness);
    if (carried.shrank) carried.letGoWork = 0.5 * (previous.force - carried.force).dot(slip);
    return carried;
}

/// @a previous carried into a step of stiffness @a stiffness and slip @a slip (CarriedSpring).
/// Inline: it runs for every node in contact, and nearly every spring keeps its stiffness.
inline CarriedSpring carrySpring(const ShearHistory::Entry& previous, double stiffness,
                                 const Vec3& slip)
{
    if (!(previous.stiffness > 0.0) || previous.stiffness == stiffness || !(stiffness > 0.0))
        return CarriedSpring{previous.force};
    return carryChangedSpring(previous, stiffness, slip);
}

/// Side @a side's new shear history @a nextHistory kept (sorted by node, as the history is,
/// when the nodes did not come in order).
void keepShearHistory(ContactSide& side, const StoredShear& stored,
                      std::vector<ShearHistory::Entry>& nextHistory)
{
    if (!stored.inOrder())
        std::sort(nextHistory.begin(), nextHistory.end(),
                  [](const auto& a, const auto& b) { return a.node < b.node; });
    side.history->replaceWith(nextHistory);
}

/// The normal spring's energy of contact @a c, whose per-node force is @a f: ½·k·d² (its mean
/// over a patch). Written as (½·(k·d))·d, as the sums always had it.
inline double nodeSpringEnergy(const NodeContact& c, const PointForce& f)
{
    return c.isPatch() ? 0.5 * f.stiffness * c.squareDepth
                       : 0.5 * (f.stiffness * c.depth) * c.depth;
}

/// Side @a side's point forces @a forces without shear springs: their elastic energy and
/// stiffness added to the sums, point force by point force (its history, if any, ends). The
/// energy is summed in a local (a register), as in addSideForces, in the same order.
void addSideSums(ContactSide& side, const std::vector<PointForce>& forces, const SidePass& pass,
                 double& elasticEnergySum, StiffnessSum& stiffness)
{
    double elasticEnergy = elasticEnergySum;
    for (size_t k = 0; k < forces.size(); ++k) {
        const PointForce& f = forces[k];
        const NodeContact* c = pass.perNodeForces ? &side.contacts[k] : nullptr;
        const double size = normalForceSize(f, c);
        if (size == 0.0 || f.stiffness <= 0.0) continue;
        // A per-node force's spring energy; the other laws' energy is added once per side.
        if (c) elasticEnergy += nodeSpringEnergy(*c, f);
        stiffness.add(f.stiffness, 0.0, c ? c->normal : Vec3(f.force / size), f.point);
    }
    if (!pass.perNodeForces && !forces.empty())
        elasticEnergy += pass.model.normal().elasticEnergy(
            side.contacts, pass.model.normalStiffness, side.weight);
    if (side.history) side.history->clear();
    elasticEnergySum = elasticEnergy;
}

/// Coulomb's limit of a node whose normal spring force is @a size: μ times the node's normal
/// force, its spring and its share of the dashpot (which the bodies feel as normal force too),
/// in proportion to its spring, so that the limits add up to μ times the contact's normal
/// force and none is cut to zero while the others keep theirs.
double coulombLimit(const SidePass& pass, double size)
{
    return pass.shearSprings.friction * std::max(0.0, size * (1.0 + pass.viscousPerForce));
}

/// Contact @a c's point force @a f given its shear force @a shear (a spring of stiffness
/// @a shearStiffness holding energy @a springEnergy), and its elastic energy, history and
/// stiffness added to the side's sums, in the order of the contacts (a side below kLaneSumsFrom
/// contacts adds so, its springs computed one by one or in lanes). Friction's work is added where the spring is computed. Inline, with
/// the energy in the caller's local: a sum kept in memory would be stored and loaded again at
/// every contact.
inline void addSpring(const NodeContact& c, PointForce& f, const Vec3& shear,
                      double shearStiffness, double springEnergy, double& elasticEnergy,
                      std::vector<ShearHistory::Entry>& nextHistory, StiffnessSum& stiffness)
{
    elasticEnergy += nodeSpringEnergy(c, f);
    nextHistory.push_back({c.node, shear, shearStiffness});
    f.force += shear;
    elasticEnergy += springEnergy;
    stiffness.add(f.stiffness, shearStiffness, c.normal, f.point);
}

/// What a side's springs add to the contact's sums (addSideWithSprings).
struct SideSprings
{
    StoredShear& stored;
    std::vector<ShearHistory::Entry>& nextHistory;
    StiffnessSum& stiffness;
    double elasticEnergy;
    double frictionWork;
};

/// The shear springs of a side with fewer contacts than a batch of lanes, one contact after
/// another (updateShearForce): for them the lanes' gathering would cost more than it saves.
void addSpringsOneByOne(const ContactSide& side, std::vector<PointForce>& forces,
                        const SidePass& pass, SideSprings& sums)
{
    double elasticEnergy = sums.elasticEnergy, frictionWork = sums.frictionWork;
    for (size_t k = 0; k < forces.size(); ++k) {
        PointForce& f = forces[k];
        const NodeContact& c = side.contacts[k];
        const double size = f.stiffness * c.depth;  // normalForceSize for a per-node law
        if (size == 0.0 || f.stiffness <= 0.0) continue;
        const double shearStiffness =
            pass.shearSprings.nodeStiffness(pass.shearPerArea, c.area, side.weight);
        const Vec3 slip =
            (side.tester->pointVelocity(f.point) - side.other->pointVelocity(f.point)) * pass.dt;
        const CarriedSpring carried = carrySpring(sums.stored.of(c.node), shearStiffness, slip);
        carried.addWork(frictionWork);
        const Vec3 shear =
            updateShearForce(carried.force, c.normal, slip, pass.meanTurn.dot(c.normal),
                             shearStiffness, coulombLimit(pass, size), &frictionWork);
        addSpring(c, f, shear, shearStiffness, 0.5 * shear.squaredNorm() / shearStiffness,
                  elasticEnergy, sums.nextHistory, sums.stiffness);
    }
    sums.elasticEnergy = elasticEnergy;
    sums.frictionWork = frictionWork;
}

/// From how many contacts a side's sums are made lane by lane (SideLaneSums.h). Below it they
/// are made contact by contact: the partials' start and join cost more than they save on a
/// small side (the law alone on a pressed face, old and new alternated, 2026-12-01: the lanes'
/// sums 0.87–0.88× as fast at 5 contacts, 0.90–0.96× at 8, 0.97× at 12, 0.98–1.05× at 16,
/// 1.03–1.09× at 32, 1.06–1.13× at 2048).
constexpr size_t kLaneSumsFrom = 16;

/// The shear springs of a side kShearLanes contacts at a time (ShearSpringLanes.h; a last
/// batch that is not full four at a time where it can, the rest lane by lane), and the side's
/// sums: those of a large side lane by lane as well (SideLaneSums.h), then added to the pair's,
/// those of a smaller one contact by contact (addSpring, addSideForces). @a kSumInLanes tells which, so that neither version
/// asks at every contact. Friction's work and the new history are added contact by contact.
/// Not inlined: its lanes' aligned arrays would enlarge the frame of every contact's law, most
/// of which (a packing's) are small enough to go one by one.
template <bool kSumInLanes>
[[gnu::noinline]] void addSideInLanes(const ContactSide& side, const ContactGrain& first,
                                      std::vector<PointForce>& forces, const SidePass& pass,
                                      SideSprings& sums, PairForces& result)
{
    double elasticEnergy = sums.elasticEnergy, frictionWork = sums.frictionWork;
    const LaneBodyMotion tester = LaneBodyMotion::of(
        side.tester->velocity, side.tester->angularVelocity, side.tester->pose.position);
    const LaneBodyMotion other = LaneBodyMotion::of(
        side.other->velocity, side.other->angularVelocity, side.other->pose.position);
    ShearSpringLanes lanes;
    NormalForceLanes normals;
    SideLaneSums laneSums(side.tester->pose.position, side.other->pose.position);
    std::array<size_t, kShearLanes> forceOf{};  // the point force in each lane
    std::array<CarriedSpring, kShearLanes> carried;
    const size_t count = forces.size();
    size_t next = 0;
    while (next < count) {
        // The next contacts that carry a force, one a lane.
        int used = 0;
        for (; next < count && used < kShearLanes; ++next) {
            const PointForce& f = forces[next];
            const NodeContact& c = side.contacts[next];
            const double size = f.stiffness * c.depth;  // normalForceSize for a per-node law
            if (size == 0.0 || f.stiffness <= 0.0) continue;
            lanes.px[used] = f.point.x();
            lanes.py[used] = f.point.y();
            lanes.pz[used] = f.point.z();
            lanes.nx[used] = c.normal.x();
            lanes.ny[used] = c.normal.y();
            lanes.nz[used] = c.normal.z();
            lanes.stiffness[used] =
                pass.shearSprings.nodeStiffness(pass.shearPerArea, c.area, side.weight);
            lanes.limit[used] = coulombLimit(pass, size);
            if constexpr (kSumInLanes) {
                normals.gx[used] = f.force.x();
                normals.gy[used] = f.force.y();
                normals.gz[used] = f.force.z();
                normals.stiffness[used] = f.stiffness;
                normals.energy[used] = nodeSpringEnergy(c, f);
            }
            forceOf[static_cast<size_t>(used++)] = next;
        }
        if (used == 0) break;
        const bool full = used == kShearLanes;
        if (full)
            lanes.slips(tester, other, pass.dt);
        else
            lanes.slipsFirst(used, tester, other, pass.dt);
        for (int l = 0; l < used; ++l) {
            const size_t lane = static_cast<size_t>(l);
            const Vec3 slip(lanes.ux[l], lanes.uy[l], lanes.uz[l]);
            carried[lane] =
                carrySpring(sums.stored.of(side.contacts[forceOf[lane]].node), lanes.stiffness[l],
                            slip);
            lanes.sx[l] = carried[lane].force.x();
            lanes.sy[l] = carried[lane].force.y();
            lanes.sz[l] = carried[lane].force.z();
        }
        if (full)
            lanes.update(pass.meanTurn);
        else
            lanes.updateFirst(used, pass.meanTurn);
        if (kSumInLanes && full)
            laneSums.add(lanes, normals);
        else if (kSumInLanes)
            laneSums.addFirst(used, lanes, normals);
        for (int l = 0; l < used; ++l) {
            const size_t lane = static_cast<size_t>(l);
            carried[lane].addWork(frictionWork);
            if (lanes.slid[l] != 0.0) frictionWork += lanes.dissipated[l];
            const NodeContact& c = side.contacts[forceOf[lane]];
            PointForce& f = forces[forceOf[lane]];
            const Vec3 shear(lanes.fx[l], lanes.fy[l], lanes.fz[l]);
            if constexpr (kSumInLanes) {
                sums.nextHistory.push_back({c.node, shear, lanes.stiffness[l]});
                f.force += shear;  // as the point forces are listed
            } else {
                addSpring(c, f, shear, lanes.stiffness[l], lanes.energy[l], elasticEnergy,
                          sums.nextHistory, sums.stiffness);
            }
        }
    }
    sums.frictionWork = frictionWork;
    if constexpr (!kSumInLanes) {
        sums.elasticEnergy = elasticEnergy;
        addSideForces(side, first, forces, result);
        return;
    }
    const SideTotals totals = laneSums.totals();
    sums.elasticEnergy = elasticEnergy + totals.elasticEnergy;
    sums.stiffness.addSide(totals, side.tester == &first);
    addSideTotals(side, first, totals, count, result);
}

/// Side @a side's point forces @a forces (a per-node law's, with shear springs) given their
/// shear springs, its history renewed (nodes that left contact lose theirs; nodes that entered
/// start from zero), and their elastic energy, friction's work, stiffness, forces and torques
/// added to the sums.
void addSideWithSprings(ContactSide& side, const ContactGrain& first,
                        std::vector<PointForce>& forces, const SidePass& pass,
                        std::vector<ShearHistory::Entry>& nextHistory, double& elasticEnergySum,
                        double& frictionWork, StiffnessSum& stiffness, PairForces& result)
{
    nextHistory.clear();
    StoredShear stored(side.history);
    SideSprings sums{stored, nextHistory, stiffness, elasticEnergySum, frictionWork};
    if (forces.size() < static_cast<size_t>(kShearLanesLeast)) {
        addSpringsOneByOne(side, forces, pass, sums);
        addSideForces(side, first, forces, result);
    } else if (forces.size() < kLaneSumsFrom) {
        addSideInLanes<false>(side, first, forces, pass, sums, result);
    } else {
        addSideInLanes<true>(side, first, forces, pass, sums, result);
    }
    keepShearHistory(side, stored, nextHistory);
    elasticEnergySum = sums.elasticEnergy;
    frictionWork = sums.frictionWork;
}

} // namespace

PairForces resolveContact(ContactSide* sides, int sideCount, const ContactModel& model,
                          double dt, std::vector<PointForce>* allForces, ContactScratch* scratch)
{
    // Most candidate pairs of a packing touch at no node in a given step: their result is a
    // contact without nodes (every field zero), and their shear history ends.
    bool anyNode = false;
    for (int s = 0; s < sideCount; ++s) anyNode = anyNode || !sides[s].contacts.empty();
    if (!anyNode) {
        for (int s = 0; s < sideCount; ++s)
            if (sides[s].history) sides[s].history->clear();
        return PairForces();
    }
    ContactScratch temporary;
    ContactScratch& work = scratch ? *scratch : temporary;
    PairForces result;
    const ContactGrain& first = *sides[0].tester;
    const ContactGrain& second = *sides[0].other;

    // The normal laws first, for every side: the dashpot is the whole contact's.
    const NormalModel& normalLaw = model.normal();
    std::vector<PointForce>* normal = work.forces;
    result.contactNodes = normalForces(sides, sideCount, model, normal);
    const bool perNodeForces = normalLaw.perNodeForces();
    const Dashpot dashpot = contactDashpot(sides, sideCount, model, normal, perNodeForces);
    result.dashpot = dashpot.coefficient;
    placeContact(sides, sideCount, normal, perNodeForces, dashpot, result);
    const ShearSpringModel shearSprings = model.tangential();
    // The turn of the shear history about the normal in this step: the pair's mean spin.
    const SidePass pass{model,
                        shearSprings,
                        perNodeForces,
                        shearSprings.active(normalLaw),
                        normalLaw.stiffnessPerArea(),
                        dashpot.viscousPerForce,
                        (0.5 * dt) * (first.angularVelocity + second.angularVelocity),
                        dt};

    // Then side by side: shear springs, elastic energy and stiffness; the forces on the bodies.
    double elasticEnergy = 0.0, frictionWork = 0.0;
    StiffnessSum stiffness(first, second);
    for (int s = 0; s < sideCount; ++s) {
        ContactSide& side = sides[s];
        std::vector<PointForce>& forces = normal[s];
        if (pass.perNodeShear && side.history) {
            addSideWithSprings(side, first, forces, pass, work.nextHistory, elasticEnergy,
                               frictionWork, stiffness, result);
        } else {
            addSideSums(side, forces, pass, elasticEnergy, stiffness);
            addSideForces(side, first, forces, result);
        }
        if (allForces) allForces->insert(allForces->end(), forces.begin(), forces.end());
        if (s == 0 && result.dashpot > 0.0) {
            if (allForces) allForces->push_back({-1, dashpot.force, dashpot.axis.centre, 0.0});
            ++result.pointForcesOnFirst;
        }
    }
    if (result.dashpot > 0.0) {
        addDashpot(dashpot, first, second, result);
        const Vec3& centre = dashpot.axis.centre;
        const Vec3& n = dashpot.axis.normal;
        if (first.mass > 0.0) result.dashpotArmOfFirst = (centre - first.pose.position).cross(n);
        if (second.mass > 0.0)
            result.dashpotArmOfSecond = (centre - second.pose.position).cross(n);
    }
    result.elasticEnergy = elasticEnergy;
    result.frictionWork = dt > 0.0 ? frictionWork : 0.0;
    result.dashpotWork = dashpot.power * dt;
    stiffness.store(result);
    return result;
}

} // namespace lsdem
