// The per-node shear spring: elastic increments, Coulomb cap, rotation with the normal and
// with the pair's spin about it, the history kept per (pair, node) through a sliding contact,
// and its objectivity: a stuck pair turning as one rigid body keeps its shear in its own frame.
#include "lsdem/contact/PairContact.h"
#include "lsdem/contact/TangentialModel.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace lsdem;

TEST(ShearSpring, ElasticBelowTheLimitAndSaturatesAtIt)
{
    const Vec3 n = Vec3::UnitZ();
    Vec3 shear = Vec3::Zero();
    // Stick: each step adds -k·Δu_t; the normal part of the slip is ignored.
    shear = updateShearForce(shear, n, Vec3(1e-3, 0, 5e-3), 0.0, 100.0, 10.0);
    EXPECT_NEAR((shear - Vec3(-0.1, 0, 0)).norm(), 0.0, 1e-15);
    // Slide: the force stops at μ|F_n| = 10 however far the node slips, along -slip.
    for (int step = 0; step < 1000; ++step) shear = updateShearForce(shear, n, Vec3(1e-3, 0, 0), 0.0, 100.0, 10.0);
    EXPECT_NEAR(shear.norm(), 10.0, 1e-12);
    EXPECT_NEAR(shear.normalized().dot(Vec3(-1, 0, 0)), 1.0, 1e-12);
    // Reversing the slip unloads elastically first.
    shear = updateShearForce(shear, n, Vec3(-1e-3, 0, 0), 0.0, 100.0, 10.0);
    EXPECT_NEAR(shear.x(), -9.9, 1e-12);
}

// What the cap takes, against the work-less-stored-energy of a force held at a cap that moves
// linearly over the step. A node sliding at a steady limit 10, slipped 0.02 at k = 100: trial 12,
// cut to 10, plastic slip 0.02 at force 10: 0.2. The limit rising to 10.5 meanwhile: the force
// (at the cap throughout) does ∫ = (10 + 10.5)/2·0.02 = 0.205 of work and the spring gains
// (10.5² − 10²)/200 = 0.05125: 0.15375. A limit falling from the stored 9 to 5 without slip
// takes what the spring lost, (9² − 5²)/200 = 0.28. A step within the limit takes nothing.
TEST(ShearSpring, CountsTheWorkOfItsSlip)
{
    const Vec3 n = Vec3::UnitZ(), slip(0.02, 0, 0);
    const auto taken = [&](const Vec3& stored, const Vec3& slipped, double limit) {
        double dissipated = 0.0;
        const Vec3 shear = updateShearForce(stored, n, slipped, 0.0, 100.0, limit, &dissipated);
        EXPECT_NEAR(shear.norm(), std::min(limit, (stored - 100.0 * slipped).norm()), 1e-12);
        return dissipated;
    };
    EXPECT_NEAR(taken(Vec3(-10, 0, 0), slip, 10.0), 0.2, 1e-12);
    EXPECT_NEAR(taken(Vec3(-10, 0, 0), slip, 10.5), 0.15375, 1e-12);
    EXPECT_NEAR(taken(Vec3(-9, 0, 0), Vec3::Zero(), 5.0), 0.28, 1e-12);
    EXPECT_EQ(taken(Vec3(-9, 0, 0), slip, 12.0), 0.0);
}

// No normal force, no shear: a limit of zero (or below, which a law should never give) leaves
// nothing, whatever was stored or slipped; a limit exactly met is not cut.
TEST(ShearSpring, ALimitOfZeroOrLessCarriesNoShear)
{
    const Vec3 n = Vec3::UnitZ(), stored(3, 4, 0), slip(1e-3, 2e-3, 0);
    EXPECT_EQ(updateShearForce(stored, n, slip, 0.0, 100.0, 0.0), Vec3::Zero());
    EXPECT_EQ(updateShearForce(stored, n, slip, 0.0, 100.0, -1.0), Vec3::Zero());
    EXPECT_EQ(updateShearForce(Vec3::Zero(), n, Vec3::Zero(), 0.0, 100.0, -1.0), Vec3::Zero());
    EXPECT_EQ(updateShearForce(stored, n, Vec3::Zero(), 0.0, 100.0, 5.0), stored);  // |stored| = 5
}

TEST(ShearSpring, TurnsWithTheNormalWithoutGainingOrLosing)
{
    const Vec3 stored(3, 4, 0);  // tangent to z
    const Vec3 turned = Eigen::AngleAxisd(0.3, Vec3::UnitY()) * Vec3::UnitZ();
    const Vec3 shear = updateShearForce(stored, turned, Vec3::Zero(), 0.0, 100.0, 1e9);
    EXPECT_NEAR(shear.dot(turned), 0.0, 1e-12);    // on the new tangent plane
    EXPECT_NEAR(shear.norm(), stored.norm(), 1e-12);  // same size: nothing created
    // No stored force and a purely normal approach: no shear appears.
    EXPECT_LT(updateShearForce(Vec3::Zero(), turned, 0.01 * turned, 0.0, 100.0, 1e9).norm(), 1e-15);
}

// The pair's spin about the normal turns the stored force by that angle (θ = 0.2 here, in one
// go: the step is second order in θ, so its direction is off by about θ³/3), keeping its size.
TEST(ShearSpring, TurnsWithThePairsSpinAboutTheNormal)
{
    const Vec3 stored(3, 4, 0), n = Vec3::UnitZ();
    const double twist = 0.02;
    const Vec3 shear = updateShearForce(stored, n, Vec3::Zero(), twist, 100.0, 1e9);
    const Vec3 exact = Eigen::AngleAxisd(twist, n) * stored;
    EXPECT_NEAR(shear.norm(), stored.norm(), 1e-12);
    EXPECT_NEAR((shear - exact).norm(), 0.0, stored.norm() * twist * twist * twist);
    EXPECT_GT((shear - stored).norm(), 0.5 * twist * stored.norm());  // it did turn
}

// Two spheres in contact, the second dragged sideways: while sticking the tangential force is
// ks*·Σ A_a·u over the contact nodes (adapted); once every node slides it is μ times the normal
// force; nodes leaving contact drop their history.
TEST(ShearSpring, SlidingSpheresReachCoulombAndKeepHistoryPerNode)
{
    std::vector<std::string> warnings;
    BakeOptions o;
    o.voxelSize = 0.05;
    o.nodeSpacing = 0.2;
    const GrainAsset ball = bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings);
    ContactGrain g0, g1;
    g0.asset = g1.asset = &ball;
    g1.index = 1;
    g1.pose.position = Vec3(10 - 0.1, 0, 0);
    g1.velocity = Vec3(0, 1.0, 0);  // mm/s, sliding in +y
    ContactModel m;
    m.formulation = Formulation::Adapted;
    m.testing = NodeTesting::OneWay;
    m.normalStiffness = 1e3;
    m.shearStiffness = 1e3;
    m.friction = 0.3;
    PairHistory history;
    NodeCheckStats stats;
    ContactModel frictionless = m;
    frictionless.friction = 0.0;
    const PairForces normalOnly = computePairContact(g0, g1, frictionless, 0.0, nullptr, stats);
    const double dt = 1e-6;  // slip 1e-6 mm per step: elastic for the first steps
    PairForces r = computePairContact(g0, g1, m, dt, &history, stats);
    double contactArea = 0;
    for (const ShearHistory::Entry& e : history.shearOnFirstNodes.entries())
        contactArea += ball.nodes.areas[size_t(e.node)];
    ASSERT_GT(history.shearOnFirstNodes.size(), 10u);
    EXPECT_TRUE(history.shearOnSecondNodes.empty());  // one-way: only grain 0's nodes tested
    // Grain 0's nodes slip by -1e-6 relative to grain 1: shear on grain 0 is +ks*·A·1e-6 in y.
    // (The normal forces of a finite node set have a small transverse part: subtract it.)
    const double shearY = r.forceOnFirst.y() - normalOnly.forceOnFirst.y();
    // Each node takes the tangential part of the slip, (1 - n_y²) of it in y; with normals
    // inside the 8° contact cap n_y² < 0.02.
    EXPECT_NEAR(shearY / (1e3 * contactArea * 1e-6), 1.0, 0.02);
    EXPECT_LT(shearY, 1e3 * contactArea * 1e-6);
    // Symmetric testing takes both grains' nodes at half weight, shear springs included, so
    // the same slip gives the same shear (up to the two node sets' areas in the cap, a few %;
    // a shear spring at full weight would double it).
    {
        ContactModel both = m, bothFrictionless = frictionless;
        both.testing = bothFrictionless.testing = NodeTesting::Symmetric;
        PairHistory fresh;
        const PairForces normal = computePairContact(g0, g1, bothFrictionless, 0.0, nullptr, stats);
        const PairForces sheared = computePairContact(g0, g1, both, dt, &fresh, stats);
        EXPECT_NEAR((sheared.forceOnFirst.y() - normal.forceOnFirst.y()) / shearY, 1.0, 0.05);
    }
    // Keep sliding (the spheres stay in place, only velocities drive the springs).
    for (int step = 0; step < 2000; ++step) r = computePairContact(g0, g1, m, 1e-4, &history, stats);
    // Every node slides: Σ μ|F_n,a| = μ·Σ|F_n,a|, which equals μ times the centre-line force
    // up to the spread of the node normals around it (a cap of half-angle 8°: cos ≥ 0.99).
    const double shearOnSecond = r.forceOnSecond.y() - normalOnly.forceOnSecond.y();
    EXPECT_NEAR(std::abs(shearOnSecond) / normalOnly.forceOnSecond.x(), 0.3, 0.3 * 0.01);
    EXPECT_LT(shearOnSecond, 0.0);  // friction opposes the second grain's motion
    // Separate the spheres: every node leaves contact and its history goes.
    g1.pose.position.x() = 10.5;
    computePairContact(g0, g1, m, 1e-4, &history, stats);
    EXPECT_TRUE(history.shearOnFirstNodes.empty());
}

// Two spheres pressed together with a stored shear, then turned as one rigid body (no relative
// motion: the same nodes in contact, at the same depths, with the same slip of zero): seen from
// the pair, nothing happens, so the shear must stay the same in the pair's own frame. Turning
// about the line of centres (the contact normal) is what a projection onto the tangent plane
// cannot follow; about a perpendicular axis the normal itself turns. Quarter turns in 1000
// steps: the carried force's direction errs by O(θ²) a step, 2.5e-6, so 0.5 % in all.
TEST(ShearSpring, AStuckPairTurningAsOneBodyKeepsItsShearInItsOwnFrame)
{
    std::vector<std::string> warnings;
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.3;
    const GrainAsset ball = bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings);
    ContactModel m;
    m.formulation = Formulation::Adapted;
    m.testing = NodeTesting::OneWay;
    m.normalStiffness = 1e3;
    m.shearStiffness = 1e3;
    m.friction = 0.5;
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0.6, 0.0, 0.8)}) {
        SCOPED_TRACE("turning about " + std::to_string(axis.x()) + " " +
                     std::to_string(axis.y()) + " " + std::to_string(axis.z()));
        ContactGrain g0, g1;
        g0.asset = g1.asset = &ball;
        g1.index = 1;
        const Vec3 centre1(10 - 0.2, 0, 0), pivot = 0.5 * centre1;
        g1.pose.position = centre1;
        PairHistory history;
        NodeCheckStats stats;
        // A shear to carry: the second sphere slid in y and z for one step.
        g1.velocity = Vec3(0, 1.0, 0.5);
        computePairContact(g0, g1, m, 1e-4, &history, stats);
        const auto totalShear = [&] {
            Vec3 sum = Vec3::Zero();
            for (const ShearHistory::Entry& e : history.shearOnFirstNodes.entries()) sum += e.force;
            return sum;
        };
        const Vec3 before = totalShear();
        const size_t nodes = history.shearOnFirstNodes.size();
        ASSERT_GT(before.norm(), 0.0);
        ASSERT_GT(nodes, 5u);
        // Turn the pair about the pivot at spin ω for a quarter turn.
        const int steps = 1000;
        const double dt = 1e-3, omega = 0.5 * kPi / (steps * dt);
        const Quat stepTurn(Eigen::AngleAxisd(omega * dt, axis.normalized()));
        Quat total = Quat::Identity();
        for (int k = 0; k < steps; ++k) {
            total = (stepTurn * total).normalized();
            for (ContactGrain* g : {&g0, &g1}) {
                const Vec3 start = g == &g0 ? Vec3::Zero() : centre1;
                g->pose.position = pivot + total * (start - pivot);
                g->pose.orientation = total;
                g->angularVelocity = omega * axis.normalized();
                // Over the step just taken, the centroid moved along the arc: its mean velocity.
                g->velocity = g->angularVelocity.cross(g->pose.position - pivot);
            }
            computePairContact(g0, g1, m, dt, &history, stats);
        }
        EXPECT_EQ(history.shearOnFirstNodes.size(), nodes);  // the same nodes in contact
        const Vec3 inOwnFrame = total.conjugate() * totalShear();
        EXPECT_LT((inOwnFrame - before).norm(), 5e-3 * before.norm())
            << "before " << before.transpose() << ", after (pair frame) "
            << inOwnFrame.transpose();
    }
}
