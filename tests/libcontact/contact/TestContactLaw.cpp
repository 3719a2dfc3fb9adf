// resolveContact on hand-made penetrating nodes (no level sets involved): action and reaction
// with torques about each centroid, the two half-weight sides of symmetric testing, the dashpot
// on the contact's approach (critical-damping fraction, no resistance to rolling), the shear
// history of the nodes now in contact and its objectivity, and the elastic energy and contact
// stiffness (translation and rotation) it reports. Every expected value is summed here by
// hand from the documented laws (docs/contact.md, docs/dynamics.md).
#include "lsdem/contact/ContactLaw.h"
#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

using namespace lsdem;

namespace {

constexpr double kKnStar = 1e3;

NodeContact node(int index, double depth, const Vec3& normal, const Vec3& point, double area)
{
    NodeContact c;
    c.node = index;
    c.depth = depth;
    c.normal = normal.normalized();
    c.point = point;
    c.area = area;
    return c;
}

/// Grain A at the origin, grain B above it; A's nodes 2 and 6 are inside B.
struct TwoGrains
{
    ContactGrain a, b;
    std::vector<NodeContact> aInB = {
        node(2, 0.1, Vec3(0, 0, -1), Vec3(0.3, 0.0, 1.0), 0.5),
        node(6, 0.05, Vec3(0.6, 0, -0.8), Vec3(-0.2, 0.4, 1.1), 0.25)};
    std::vector<NodeContact> bInA = {node(1, 0.08, Vec3(0, 0.28, 0.96), Vec3(0.1, 0.1, 0.95), 0.4)};

    TwoGrains()
    {
        a.pose.position = Vec3(0, 0, 0);
        b.pose.position = Vec3(0.1, -0.2, 2.0);
        b.index = 1;
    }

    /// Symmetric testing: A's nodes in B, then B's in A, each at half weight.
    void halfWeightSides(ContactSide sides[2]) const
    {
        sides[0].tester = &a;
        sides[0].other = &b;
        sides[0].contacts = aInB;
        sides[0].weight = 0.5;
        sides[1].tester = &b;
        sides[1].other = &a;
        sides[1].contacts = bInA;
        sides[1].weight = 0.5;
    }
};

ContactModel adapted(double ks = 0.0, double friction = 0.0, double restitution = 1.0)
{
    ContactModel m;
    m.formulation = Formulation::Adapted;
    m.normalStiffness = kKnStar;
    m.shearStiffness = ks;
    m.friction = friction;
    m.damping = ViscousDamping(restitution);
    return m;
}

/// The adapted normal force of one node at weight @a w.
Vec3 adaptedForce(const NodeContact& c, double w)
{
    return w * kKnStar * c.depth * c.area * c.normal;
}

/// The nodes of a ball (radius @a radius, its centre @a depth less than that above a wall at
/// z = 0) on rings of radius @a rings about its lowest point, eight a ring (one at 0), that lie
/// below the wall: depth, the wall's normal, the point halfway to the wall, area 0.05 each.
std::vector<NodeContact> ballCapOnAWall(double radius, double depth,
                                        std::initializer_list<double> rings)
{
    std::vector<NodeContact> cap;
    for (double rho : rings) {
        const int count = rho == 0.0 ? 1 : 8;
        for (int k = 0; k < count; ++k) {
            const double angle = 2 * kPi * k / count;
            const Vec3 surface(rho * std::cos(angle), rho * std::sin(angle),
                               radius - depth - std::sqrt(radius * radius - rho * rho));
            if (surface.z() >= 0.0) continue;
            cap.push_back(node(int(cap.size()), -surface.z(), Vec3::UnitZ(),
                               surface - 0.5 * surface.z() * Vec3::UnitZ(), 0.05));
        }
    }
    return cap;
}

void expectVecNear(const Vec3& actual, const Vec3& expected, double tolerance)
{
    EXPECT_LT((actual - expected).norm(), tolerance)
        << actual.transpose() << " vs " << expected.transpose();
}

} // namespace

// One side at full weight: A gets Σ F at the contact points, B the opposite; each torque is
// about its own centroid, so the two torques differ by (x_B - x_A) × F.
TEST(ContactLaw, ActionEqualsReactionAndTorquesAreAboutEachCentroid)
{
    TwoGrains g;
    ContactSide side;
    side.tester = &g.a;
    side.other = &g.b;
    side.contacts = g.aInB;
    std::vector<PointForce> all;
    const PairForces r = resolveContact(&side, 1, adapted(), 0.0, &all);

    Vec3 force = Vec3::Zero(), torqueA = Vec3::Zero(), torqueB = Vec3::Zero();
    for (const NodeContact& c : g.aInB) {
        const Vec3 f = adaptedForce(c, 1.0);
        force += f;
        torqueA += (c.point - g.a.pose.position).cross(f);
        torqueB -= (c.point - g.b.pose.position).cross(f);
    }
    const double tol = 1e-13 * force.norm();  // a handful of sums of numbers of size ~|F|
    expectVecNear(r.forceOnFirst, force, tol);
    expectVecNear(r.forceOnSecond, -force, tol);
    expectVecNear(r.torqueOnFirst, torqueA, tol);
    expectVecNear(r.torqueOnSecond, torqueB, tol);
    // The total moment about any point vanishes (equal and opposite forces at the same points).
    expectVecNear(r.torqueOnFirst + r.torqueOnSecond + g.a.pose.position.cross(r.forceOnFirst) +
                      g.b.pose.position.cross(r.forceOnSecond),
                  Vec3::Zero(), tol);
    EXPECT_EQ(r.contactNodes, 2);
    EXPECT_EQ(r.pointForcesOnFirst, 2);
    ASSERT_EQ(all.size(), 2u);
    for (size_t k = 0; k < all.size(); ++k) {
        expectVecNear(all[k].force, adaptedForce(g.aInB[k], 1.0), tol);
        EXPECT_EQ(all[k].point, g.aInB[k].point);
        EXPECT_EQ(all[k].node, g.aInB[k].node);
    }
}

// Symmetric testing: side 0 (A's nodes in B) and side 1 (B's nodes in A), each at half weight.
// A gets half of its own nodes' forces and the reaction to half of B's; the point forces are
// listed side by side, each as it acts on its side's tester.
TEST(ContactLaw, SymmetricSidesAddAtHalfWeight)
{
    TwoGrains g;
    ContactSide sides[2];
    g.halfWeightSides(sides);
    std::vector<PointForce> all;
    const PairForces r = resolveContact(sides, 2, adapted(), 0.0, &all);

    Vec3 onA = Vec3::Zero(), torqueA = Vec3::Zero(), torqueB = Vec3::Zero();
    for (const NodeContact& c : g.aInB) {
        const Vec3 f = adaptedForce(c, 0.5);
        onA += f;
        torqueA += (c.point - g.a.pose.position).cross(f);
        torqueB -= (c.point - g.b.pose.position).cross(f);
    }
    for (const NodeContact& c : g.bInA) {
        const Vec3 f = adaptedForce(c, 0.5);  // on B
        onA -= f;
        torqueB += (c.point - g.b.pose.position).cross(f);
        torqueA -= (c.point - g.a.pose.position).cross(f);
    }
    const double tol = 1e-13 * 50.0;
    expectVecNear(r.forceOnFirst, onA, tol);
    expectVecNear(r.forceOnSecond, -onA, tol);
    expectVecNear(r.torqueOnFirst, torqueA, tol);
    expectVecNear(r.torqueOnSecond, torqueB, tol);
    EXPECT_EQ(r.contactNodes, 3);
    EXPECT_EQ(r.pointForcesOnFirst, 2);
    ASSERT_EQ(all.size(), 3u);
    expectVecNear(all[2].force, adaptedForce(g.bInA[0], 0.5), tol);  // on B, B's node
    // The contact stiffness Σ k·n nᵀ of every normal point force, both sides (no shear); in
    // rotation Σ k·w wᵀ with w = (p − c) × n about each centroid c (both may move).
    Mat3 k = Mat3::Zero(), kA = Mat3::Zero(), kB = Mat3::Zero();
    for (const auto* list : {&g.aInB, &g.bInA})
        for (const NodeContact& c : *list) {
            const double kc = 0.5 * kKnStar * c.area;
            k += kc * c.normal * c.normal.transpose();
            const Vec3 wA = (c.point - g.a.pose.position).cross(c.normal);
            const Vec3 wB = (c.point - g.b.pose.position).cross(c.normal);
            kA += kc * wA * wA.transpose();
            kB += kc * wB * wB.transpose();
        }
    EXPECT_LT((r.translationalStiffness - k).norm(), 1e-12 * k.norm());
    // (The bodies' masses are 0 here: immovable, so no rotational stiffness is summed.)
    EXPECT_TRUE(r.rotationalStiffnessOfFirst.isZero());
    TwoGrains movable = g;
    movable.a.mass = 1.0;
    movable.b.mass = 2.0;
    ContactSide movableSides[2];
    movable.halfWeightSides(movableSides);
    const PairForces rm = resolveContact(movableSides, 2, adapted(), 0.0, nullptr);
    EXPECT_LT((rm.rotationalStiffnessOfFirst - kA).norm(), 1e-12 * kA.norm());
    EXPECT_LT((rm.rotationalStiffnessOfSecond - kB).norm(), 1e-12 * kB.norm());
    // ½|F|²/k = ½·k·d² per point force.
    double energy = 0.0;
    for (const NodeContact& c : g.aInB) energy += 0.25 * kKnStar * c.area * c.depth * c.depth;
    for (const NodeContact& c : g.bInA) energy += 0.25 * kKnStar * c.area * c.depth * c.depth;
    EXPECT_NEAR(r.elasticEnergy, energy, 1e-14 * energy);
}

// The laws without per-node forces store the potential of their force: single-node ½·kn·d_max²
// per side, volume ½·kv·Σ A·d² (whose derivative along the depths is its force kv·Σ A·d; the
// ½|F|²/K of a linear spring would hold for a flat patch only). At half weight per side.
TEST(ContactLaw, SingleNodeAndVolumeStoreTheirForcesPotential)
{
    TwoGrains g;
    for (const Formulation law : {Formulation::SingleNode, Formulation::Volume}) {
        SCOPED_TRACE(formulationName(law));
        ContactModel m = adapted();
        m.formulation = law;
        m.normalStiffness = law == Formulation::SingleNode ? 1e6 : kKnStar;
        ContactSide sides[2];
        g.halfWeightSides(sides);
        const PairForces r = resolveContact(sides, 2, m, 0.0, nullptr, nullptr);
        double energy = 0.0;
        for (const auto* list : {&g.aInB, &g.bInA}) {
            double deepest = 0.0, sum = 0.0;
            for (const NodeContact& c : *list) {
                deepest = std::max(deepest, c.depth);
                sum += c.area * c.depth * c.depth;
            }
            energy += law == Formulation::SingleNode ? 0.25 * 1e6 * deepest * deepest
                                                     : 0.25 * kKnStar * sum;
        }
        EXPECT_NEAR(r.elasticEnergy, energy, 1e-14 * energy);
    }
}

// A flat contact of stiffness K = Σ kn*·A closing at speed v between masses m_A and m_B: the
// dashpot adds 2β·sqrt(m·K)·v against the approach, with m the reduced mass (or the moving
// body's mass against an immovable one) and β the ratio for the contact's exponent
// p = (1 + 1/n)·δ_max·K/P (n = (Σ A)²/Σ A², the nodes' effective count). Opening, it pulls,
// but never more than the elastic force pushes. Tangential motion is not damped.
TEST(ContactLaw, DashpotIsTheCriticalFractionOfTheWholeContact)
{
    TwoGrains g;
    const std::vector<NodeContact> flat = {node(0, 0.1, -Vec3::UnitZ(), Vec3(0.2, 0, 1), 0.25),
                                           node(1, 0.04, -Vec3::UnitZ(), Vec3(-0.2, 0, 1), 0.5),
                                           node(4, 0.02, -Vec3::UnitZ(), Vec3(0, 0.3, 1), 0.125)};
    double elastic = 0.0, stiffness = 0.0;
    for (const NodeContact& c : flat) {
        elastic += kKnStar * c.depth * c.area;
        stiffness += kKnStar * c.area;
    }
    const double restitution = 0.4, v = 2.0;
    double areas = 0.0, squares = 0.0;
    for (const NodeContact& c : flat) {
        areas += c.area;
        squares += c.area * c.area;
    }
    const double exponent = (1.0 + squares / (areas * areas)) * 0.1 * stiffness / elastic;
    // β between the table's exponents either side (steps of 1/8), linearly.
    const double position = (exponent - 1.0) / 0.125, below = std::floor(position);
    const double beta = (1.0 - (position - below)) *
                            dampingRatioFor(restitution, 1.0 + 0.125 * below) +
                        (position - below) * dampingRatioFor(restitution, 1.0 + 0.125 * (below + 1));
    ASSERT_GT(exponent, 1.0);
    struct Masses { double a, b, effective; };
    for (const Masses m : {Masses{2.0, 3.0, 1.2}, Masses{2.0, 0.0, 2.0}, Masses{0.0, 3.0, 3.0}}) {
        g.a.mass = m.a;
        g.b.mass = m.b;
        for (double speed : {v, -v}) {
            g.a.velocity = Vec3(0.7, -0.1, 0.5 * speed);  // A up (toward B), B down
            g.b.velocity = Vec3(0.0, 0.4, -0.5 * speed);
            ContactSide side;
            side.tester = &g.a;
            side.other = &g.b;
            side.contacts = flat;
            const PairForces r =
                resolveContact(&side, 1, adapted(0, 0, restitution), 0.0, nullptr);
            const double dashpot = 2 * beta * std::sqrt(m.effective * stiffness) * speed;
            EXPECT_NEAR(r.forceOnFirst.z(), -std::max(0.0, elastic + dashpot), 1e-12 * elastic)
                << m.a << " " << m.b << " " << speed;
            EXPECT_NEAR(r.forceOnFirst.x(), 0.0, 1e-13 * elastic);  // tangential motion: no
            EXPECT_NEAR(r.forceOnFirst.y(), 0.0, 1e-13 * elastic);  // dashpot, no shear
            EXPECT_NEAR(r.dashpot, 2 * beta * std::sqrt(m.effective * stiffness),
                        1e-12 * r.dashpot);
        }
    }
    // Neither body can move: no dashpot.
    g.a.mass = g.b.mass = 0.0;
    ContactSide side;
    side.tester = &g.a;
    side.other = &g.b;
    side.contacts = flat;
    EXPECT_NEAR(resolveContact(&side, 1, adapted(0, 0, restitution), 0.0, nullptr)
                    .forceOnFirst.z(),
                -elastic, 1e-13 * elastic);

    // Spinning bodies: the dashpot damps their relative velocity at the contact's
    // stiffness-weighted centre, along its normal, and acts there (one point force, listed
    // after the side's own).
    g.a.mass = 2.0;
    g.b.mass = 3.0;
    g.a.velocity = g.b.velocity = Vec3::Zero();
    g.a.angularVelocity = Vec3(0.0, 5.0, 0.0);
    g.b.angularVelocity = Vec3(1.0, 0.0, 0.0);
    Vec3 centre = Vec3::Zero(), elasticForce = Vec3::Zero(), elasticTorque = Vec3::Zero();
    for (const NodeContact& c : flat) {
        const double k = kKnStar * c.area;
        centre += k * c.point / stiffness;
        elasticForce += k * c.depth * c.normal;
        elasticTorque += (c.point - g.a.pose.position).cross(k * c.depth * c.normal);
    }
    const Vec3 relative = g.a.angularVelocity.cross(centre - g.a.pose.position) -
                          g.b.angularVelocity.cross(centre - g.b.pose.position);
    const Vec3 n = -Vec3::UnitZ();
    const Vec3 damping = -2 * beta * std::sqrt(1.2 * stiffness) * relative.dot(n) * n;
    std::vector<PointForce> all;
    const PairForces r = resolveContact(&side, 1, adapted(0, 0, restitution), 0.0, &all);
    expectVecNear(r.forceOnFirst, elasticForce + damping, 1e-13 * elastic);
    expectVecNear(r.torqueOnFirst,
                  elasticTorque + (centre - g.a.pose.position).cross(damping), 1e-13 * elastic);
    ASSERT_EQ(all.size(), flat.size() + 1);
    EXPECT_EQ(all.back().node, -1);
    expectVecNear(all.back().point, centre, 1e-15);
    expectVecNear(all.back().force, damping, 1e-13 * elastic);
    EXPECT_EQ(r.pointForcesOnFirst, int(flat.size()) + 1);
}

// A ball rolling on a wall without slip turns about its contact point: its nodes ahead of that
// point move into the wall and those behind move out, while the contact as a whole neither
// approaches nor recedes. The dashpot must not turn that into a torque against the rolling
// (a dashpot per node did, and a rolling ball slowed down): with a cap of nodes symmetric
// about the contact point, the forces and torque are those of the springs alone.
TEST(ContactLaw, RollingWithoutSlipIsNotDamped)
{
    const double radius = 5.0, depth = 0.05;
    ContactGrain ball, wall;
    ball.pose.position = Vec3(0, 0, radius - depth);
    ball.mass = 4e-6;
    ball.angularVelocity = Vec3(0.0, 20.0, 0.0);  // rolls along +x at v = ω·R: the point
    ball.velocity = -ball.angularVelocity.cross(Vec3(0, 0, -radius));  // below it is at rest
    // Rings of nodes of the ball's surface around its lowest point, below the wall (z < 0).
    const std::vector<NodeContact> cap = ballCapOnAWall(radius, depth, {0.0, 0.25, 0.5});
    ASSERT_GT(cap.size(), 9u);
    ContactSide side;
    side.tester = &ball;
    side.other = &wall;
    side.contacts = cap;
    const PairForces damped = resolveContact(&side, 1, adapted(0, 0, 0.3), 0.0, nullptr);
    const PairForces elastic = resolveContact(&side, 1, adapted(), 0.0, nullptr);
    EXPECT_GT(damped.dashpot, 0.0);
    const double scale = elastic.forceOnFirst.norm() * radius;
    expectVecNear(damped.forceOnFirst, elastic.forceOnFirst, 1e-12 * elastic.forceOnFirst.norm());
    expectVecNear(damped.torqueOnFirst, elastic.torqueOnFirst, 1e-12 * scale);
    // (Each node's own normal velocity, ±ω·x, is far from zero: a per-node dashpot would act.)
    const double nodeSpeed = std::abs(ball.pointVelocity(cap.back().point).z());
    EXPECT_GT(nodeSpeed, 1.0);
}

// Coulomb's limit for a whole contact: sliding in gross slip, the shear springs of a cap of
// nodes (deep in the middle, shallow at the rim) take μ times the contact's normal force,
// springs and dashpot together, and no more, also while the grains part and the dashpot pulls.
// Each node's limit takes a share of the dashpot in proportion to its spring; a share in
// proportion to its stiffness alone cut the shallow nodes' limits at zero while the deep ones
// kept theirs, so the limits added up to more than μ·N (friction with no normal force at all).
TEST(ContactLaw, CoulombLimitsAddUpToMuTimesTheNormalForceWhileTheGrainsPart)
{
    const double radius = 5.0, depth = 0.05, mu = 0.3, ks = 500.0, dt = 1e-6;
    ContactGrain ball, wall;
    ball.pose.position = Vec3(0, 0, radius - depth);
    ball.mass = 4e-6;
    const std::vector<NodeContact> cap = ballCapOnAWall(radius, depth, {0.0, 0.2, 0.35, 0.45, 0.5});
    double springs = 0.0, stiffness = 0.0;
    for (const NodeContact& c : cap) {
        springs += kKnStar * c.area * c.depth;
        stiffness += kKnStar * c.area;
    }
    ASSERT_GT(cap.size(), 20u);
    bool partWayWithShallowNodesBelowTheMeanShare = false;
    for (double parting : {0.0, 1.0, 10.0, 100.0, 300.0, 550.0, 650.0, 750.0, 1e5}) {
        ball.velocity = Vec3(2.0, 0.0, parting);  // sliding along +x, moving off the wall
        ShearHistory history;
        for (const NodeContact& c : cap) history.append(c.node, Vec3(-1e3, 0.0, 0.0));  // saturated
        ContactSide side;
        side.tester = &ball;
        side.other = &wall;
        side.contacts = cap;
        side.history = &history;
        const PairForces r = resolveContact(&side, 1, adapted(ks, mu, 0.3), dt, nullptr);
        const double normal = r.forceOnFirst.z();
        const double shear = std::hypot(r.forceOnFirst.x(), r.forceOnFirst.y());
        EXPECT_GE(normal, -1e-12 * springs) << parting;
        EXPECT_NEAR(shear, mu * normal, 1e-12 * springs) << parting;
        EXPECT_LT(r.forceOnFirst.x(), 0.0 + 1e-12 * springs);  // against the sliding
        // The case that tells the two shares apart: the dashpot pulls part of the springs'
        // force back, more than the shallowest node's spring per unit stiffness.
        const double viscous = normal - springs;
        if (normal > 0.01 * springs && viscous < 0.0 &&
            cap.back().depth + viscous / stiffness < 0.0)
            partWayWithShallowNodesBelowTheMeanShare = true;
    }
    EXPECT_TRUE(partWayWithShallowNodesBelowTheMeanShare);
}

// After a step the history holds exactly the nodes now in contact: a node that left loses its
// shear, a node that entered starts from zero and takes -k_t·Δu_t, a node that stayed adds the
// increment to what it had (and is capped at μ·|F_n|). k_t = ks*·A·weight (adapted).
TEST(ContactLaw, ShearHistoryIsReplacedByTheNodesNowInContact)
{
    TwoGrains g;
    g.a.velocity = Vec3(3.0, -1.0, 0.0);
    g.b.velocity = Vec3(-1.0, 1.0, 0.0);
    const double ks = 400.0, mu = 0.5, dt = 1e-3;
    ShearHistory history = {{1, Vec3(0.01, 0.0, 0.0)},   // left contact
                             {2, Vec3(0.02, -0.01, 0.0)}}; // stays (tangent to -z)
    ContactSide side;
    side.tester = &g.a;
    side.other = &g.b;
    side.contacts = g.aInB;  // nodes 2 and 6: 6 enters
    side.history = &history;
    const PairForces r = resolveContact(&side, 1, adapted(ks, mu), dt, nullptr);

    ASSERT_EQ(history.size(), 2u);
    ASSERT_TRUE(history.contains(2));
    ASSERT_TRUE(history.contains(6));
    const Vec3 slip = (g.a.velocity - g.b.velocity) * dt;  // no spin: uniform
    // Node 2, normal -z: tangential slip (4e-3, -2e-3, 0), k_t = 400·0.5 = 200.
    const Vec3 shear2 = Vec3(0.02, -0.01, 0.0) - 200.0 * Vec3(4e-3, -2e-3, 0.0);
    expectVecNear(history.force(2), shear2, 1e-15);
    // Node 6 from zero: k_t = 400·0.25 = 100 times the slip minus its normal part.
    const Vec3 n6 = g.aInB[1].normal;
    const Vec3 shear6 = -100.0 * (slip - slip.dot(n6) * n6);
    expectVecNear(history.force(6), shear6, 1e-15);
    EXPECT_LT(shear2.norm(), mu * 50.0);  // below the cap μ·kn*·d·A
    EXPECT_LT(shear6.norm(), mu * 12.5);

    const Vec3 normal = adaptedForce(g.aInB[0], 1.0) + adaptedForce(g.aInB[1], 1.0);
    expectVecNear(r.forceOnFirst, normal + shear2 + shear6, 1e-13);
    expectVecNear(r.forceOnSecond, -(normal + shear2 + shear6), 1e-13);
    // Energy: ½k d² per normal spring, ½|F_t|²/k_t per shear spring.
    const double energy = 0.5 * kKnStar * 0.5 * 0.01 + 0.5 * kKnStar * 0.25 * 0.0025 +
                          0.5 * shear2.squaredNorm() / 200.0 + 0.5 * shear6.squaredNorm() / 100.0;
    EXPECT_NEAR(r.elasticEnergy, energy, 1e-14 * energy);

    // Slide far: node 2 saturates at μ·|F_n| = 25 along its (stored - increment) direction.
    history = {{2, Vec3(30.0, 40.0, 0.0)}};
    side.contacts = {g.aInB[0]};
    resolveContact(&side, 1, adapted(ks, mu), dt, nullptr);
    const Vec3 unlimited = Vec3(30.0, 40.0, 0.0) - 200.0 * Vec3(4e-3, -2e-3, 0.0);
    expectVecNear(history.force(2), 25.0 * unlimited.normalized(), 1e-13);

    // No step (dt = 0): a stored tangential shear is carried over unchanged.
    history = {{2, Vec3(0.5, 0.25, 0.0)}};
    resolveContact(&side, 1, adapted(ks, mu), 0.0, nullptr);
    EXPECT_EQ(history.force(2), Vec3(0.5, 0.25, 0.0));

    // Nodes out of contact: the history empties.
    side.contacts.clear();
    const PairForces none = resolveContact(&side, 1, adapted(ks, mu), dt, nullptr);
    EXPECT_TRUE(history.empty());
    EXPECT_EQ(none.forceOnFirst, Vec3::Zero());
    EXPECT_EQ(none.contactNodes, 0);
}

// No history to carry (null), or a law without per-node forces: no shear force, and a history
// given to such a law ends empty.
TEST(ContactLaw, NoShearWithoutHistoryOrPerNodeForces)
{
    TwoGrains g;
    g.a.velocity = Vec3(3.0, -1.0, 0.0);
    ContactSide side;
    side.tester = &g.a;
    side.other = &g.b;
    side.contacts = g.aInB;
    const Vec3 normal = adaptedForce(g.aInB[0], 1.0) + adaptedForce(g.aInB[1], 1.0);
    expectVecNear(resolveContact(&side, 1, adapted(400, 0.5), 1e-3, nullptr).forceOnFirst,
                  normal, 1e-13);

    ShearHistory history = {{2, Vec3(1.0, 0.0, 0.0)}};
    side.history = &history;
    ContactModel volume = adapted(400, 0.5);
    volume.formulation = Formulation::Volume;
    std::vector<PointForce> all;
    const PairForces r = resolveContact(&side, 1, volume, 1e-3, &all);
    EXPECT_TRUE(history.empty());
    ASSERT_EQ(all.size(), 1u);  // the pooled force, with no shear added
    std::vector<PointForce> pooled;
    normalModel(Formulation::Volume).forces(g.aInB, kKnStar, 1.0, pooled);
    expectVecNear(r.forceOnFirst, pooled[0].force, 1e-13);
}

// A candidate pair touching at no node this step (most pairs of a packing): every field of
// the result is zero, no point force is reported, and each side's shear history ends, as a
// contact's does when its last node leaves. The same sides with nodes give forces and keep
// the history, so the check is not of an empty law.
TEST(ContactLaw, APairWithoutNodesGivesTheZeroResultAndEndsItsHistory)
{
    TwoGrains g;
    g.b.velocity = Vec3(0.0, 0.0, -0.3);
    ShearHistory onA, onB;
    onA.append(2, Vec3(0.01, 0.0, 0.0));
    onB.append(1, Vec3(0.0, -0.02, 0.0));
    ContactSide sides[2];
    g.halfWeightSides(sides);
    sides[0].contacts.clear();
    sides[1].contacts.clear();
    sides[0].history = &onA;
    sides[1].history = &onB;
    std::vector<PointForce> all;
    ContactScratch scratch;
    const PairForces r = resolveContact(sides, 2, adapted(5e2, 0.5, 0.5), 1e-6, &all, &scratch);
    const PairForces none;
    EXPECT_EQ(r.forceOnFirst, none.forceOnFirst);
    EXPECT_EQ(r.forceOnSecond, none.forceOnSecond);
    EXPECT_EQ(r.torqueOnFirst, none.torqueOnFirst);
    EXPECT_EQ(r.torqueOnSecond, none.torqueOnSecond);
    EXPECT_EQ(r.translationalStiffness, none.translationalStiffness);
    EXPECT_EQ(r.rotationalStiffnessOfFirst, none.rotationalStiffnessOfFirst);
    EXPECT_EQ(r.rotationalStiffnessOfSecond, none.rotationalStiffnessOfSecond);
    EXPECT_EQ(r.contactNodes, 0);
    EXPECT_EQ(r.pointForcesOnFirst, 0);
    EXPECT_EQ(r.elasticEnergy, 0.0);
    EXPECT_EQ(r.dashpot, 0.0);
    EXPECT_EQ(r.frictionWork, 0.0);
    EXPECT_EQ(r.dashpotWork, 0.0);
    EXPECT_EQ(r.centre, none.centre);
    EXPECT_EQ(r.normal, none.normal);
    EXPECT_TRUE(all.empty());
    EXPECT_TRUE(onA.empty());
    EXPECT_TRUE(onB.empty());

    g.halfWeightSides(sides);
    sides[0].history = &onA;
    sides[1].history = &onB;
    const PairForces touching =
        resolveContact(sides, 2, adapted(5e2, 0.5, 0.5), 1e-6, &all, &scratch);
    EXPECT_GT(touching.forceOnFirst.norm(), 0.0);
    EXPECT_EQ(touching.contactNodes, 3);
    EXPECT_FALSE(all.empty());
    EXPECT_FALSE(onA.empty());
    EXPECT_FALSE(onB.empty());
}

// A face of 1 to 40 nodes with shear springs, both bodies moving and turning, over three steps
// (stored shear carried, some springs at Coulomb's cap): whatever the count (a side of four or
// more has its springs computed eight lanes at a time, and one of 16 or more its sums as well,
// SideLaneSums.h; a last batch may be part-filled, four lanes at once and the rest one by one,
// or all one by one), the pair's force and torques are the sums
// of the listed point forces, the stiffness is Σ k_n·n nᵀ + k_t·(I − n nᵀ) in translation and
// Σ k_n·w wᵀ + k_t·[r×](I − n nᵀ)[r×]ᵀ about each centroid (w = r × n), and the energy
// Σ ½k_n·d² + ½|F_t|²/k_t, with k_n = kn*·A·weight and k_t = ks*·A·weight. Node 2 has no area
// (no force, no spring): it is skipped, not summed. Also: a sparse face (only every seventh
// node has an area, so that a side of 16 may fill no full batch), a bare one (no node has an
// area: nothing to sum) and symmetric testing (a second side, B's nodes in A, at half weight
// each: its sums belong to the other body first).
TEST(ContactLaw, AFaceSumsItsPointForcesStiffnessAndEnergyWhateverItsNodeCount)
{
    enum class Kind { Plain, Sparse, Bare, Symmetric };
    struct Face
    {
        int count;
        Kind kind;
    };
    const double ks = 400.0, mu = 0.3, dt = 1e-3;
    std::vector<Face> faces;
    for (int count : {1, 2, 3, 4, 5, 7, 8, 9, 12, 13, 15, 16, 17, 18, 19, 20, 23, 24, 28, 40})
        faces.push_back({count, Kind::Plain});
    faces.insert(faces.end(), {{16, Kind::Sparse}, {40, Kind::Sparse}, {16, Kind::Bare},
                               {5, Kind::Symmetric}, {16, Kind::Symmetric},
                               {23, Kind::Symmetric}});
    for (const Face& face : faces) {
        const int count = face.count;
        const bool symmetric = face.kind == Kind::Symmetric;
        SCOPED_TRACE("nodes: " + std::to_string(count) + ", kind " +
                     std::to_string(static_cast<int>(face.kind)));
        ContactGrain a, b;
        a.pose.position = Vec3(0.1, -0.2, -1.0);
        b.pose.position = Vec3(-0.3, 0.2, 1.2);
        b.index = 1;
        a.mass = 1.0;
        b.mass = 3.0;
        a.velocity = Vec3(2.0, -1.0, 0.5);
        b.velocity = Vec3(-1.0, 0.5, 0.0);
        a.angularVelocity = Vec3(0.5, 2.0, -3.0);
        b.angularVelocity = Vec3(-1.0, 0.0, 4.0);
        // Side 0: A's nodes in B (pushed along about +z); side 1: B's nodes in A (about −z).
        const int sideCount = symmetric ? 2 : 1;
        const double weight = symmetric ? 0.5 : 1.0;
        std::vector<NodeContact> nodes[2];
        for (int s = 0; s < sideCount; ++s)
            for (int i = 0; i < count; ++i) {
                const double x = 0.1 * (i % 4) + 0.03 * s, y = 0.1 * (i / 4);
                const Vec3 n(0.05 * std::sin(1.0 + i + s), 0.04 * std::cos(2.0 * i),
                             s == 0 ? 1.0 : -1.0);
                const bool bare = face.kind == Kind::Bare ||
                                  (face.kind == Kind::Sparse ? i % 7 != 0 : i == 2);
                nodes[s].push_back(node(i, 0.01 + 0.002 * ((i + s) % 3), n, Vec3(x, y, 0.0),
                                        bare ? 0.0 : 0.01 * (1.0 + 0.1 * i)));
            }
        ShearHistory histories[2];
        ContactSide sides[2];
        for (int s = 0; s < sideCount; ++s) {
            sides[s].tester = s == 0 ? &a : &b;
            sides[s].other = s == 0 ? &b : &a;
            sides[s].contacts = nodes[s];
            sides[s].history = &histories[s];
            sides[s].weight = weight;
        }
        std::vector<PointForce> all;
        PairForces r;
        for (int step = 0; step < 3; ++step) {
            all.clear();
            r = resolveContact(sides, sideCount, adapted(ks, mu), dt, &all);
        }
        ASSERT_EQ(all.size(), static_cast<size_t>(sideCount * count));
        Vec3 force = Vec3::Zero(), torqueA = Vec3::Zero(), torqueB = Vec3::Zero();
        Mat3 k = Mat3::Zero(), kA = Mat3::Zero(), kB = Mat3::Zero();
        double energy = 0.0, scale = 0.0;
        int capped = 0;
        size_t bearing = 0;  // nodes that carry a force, so hold a spring
        for (int s = 0; s < sideCount; ++s)
            for (int i = 0; i < count; ++i) {
                const NodeContact& c = nodes[s][static_cast<size_t>(i)];
                const Vec3& f = all[static_cast<size_t>(s * count + i)].force;  // on the tester
                const Vec3 onA = s == 0 ? f : Vec3(-f);
                force += onA;
                torqueA += (c.point - a.pose.position).cross(onA);
                torqueB -= (c.point - b.pose.position).cross(onA);
                scale = std::max(scale, f.norm());
                const double kn = weight * kKnStar * c.area, kt = weight * ks * c.area;
                if (kn == 0.0) {
                    EXPECT_EQ(f, Vec3::Zero());
                    continue;
                }
                ++bearing;
                const Vec3 shear = f - adaptedForce(c, weight);
                EXPECT_NEAR(shear.dot(c.normal), 0.0, 1e-12 * scale);
                capped += shear.norm() > (1.0 - 1e-9) * mu * kn * c.depth ? 1 : 0;
                const Mat3 tangent = Mat3::Identity() - c.normal * c.normal.transpose();
                k += kn * c.normal * c.normal.transpose() + kt * tangent;
                for (const auto& [centre, sum] : {std::pair{a.pose.position, &kA},
                                                  std::pair{b.pose.position, &kB}}) {
                    const Vec3 lever = c.point - centre;
                    Mat3 cross;
                    cross << 0, -lever.z(), lever.y(), lever.z(), 0, -lever.x(), -lever.y(),
                        lever.x(), 0;
                    const Vec3 w = lever.cross(c.normal);
                    *sum += kn * w * w.transpose() + kt * cross * tangent * cross.transpose();
                }
                energy += 0.5 * kn * c.depth * c.depth + 0.5 * shear.squaredNorm() / kt;
            }
        EXPECT_EQ(r.contactNodes, sideCount * count);
        EXPECT_EQ(r.pointForcesOnFirst, count);
        EXPECT_EQ(histories[0].size() + histories[1].size(), bearing);
        if (face.kind == Kind::Bare) {  // nothing carries a force: every sum is zero
            EXPECT_EQ(r.forceOnFirst, Vec3::Zero());
            EXPECT_EQ(r.torqueOnSecond, Vec3::Zero());
            EXPECT_EQ(r.elasticEnergy, 0.0);
            EXPECT_TRUE(r.translationalStiffness.isZero(0.0));
            EXPECT_TRUE(r.rotationalStiffnessOfFirst.isZero(0.0));
            continue;
        }
        if (count >= 8 && face.kind == Kind::Plain) {
            EXPECT_GT(capped, 0);  // some springs slide (the lanes' cap)
        }
        const double tol = 1e-12 * scale;  // a few dozen sums of numbers of size ≤ scale
        expectVecNear(r.forceOnFirst, force, tol);
        expectVecNear(r.forceOnSecond, -force, tol);
        expectVecNear(r.torqueOnFirst, torqueA, tol);
        expectVecNear(r.torqueOnSecond, torqueB, tol);
        EXPECT_LT((r.translationalStiffness - k).norm(), 1e-12 * k.norm());
        EXPECT_LT((r.rotationalStiffnessOfFirst - kA).norm(), 1e-12 * kA.norm());
        EXPECT_LT((r.rotationalStiffnessOfSecond - kB).norm(), 1e-12 * kB.norm());
        EXPECT_NEAR(r.elasticEnergy, energy, 1e-12 * energy);
    }
}
