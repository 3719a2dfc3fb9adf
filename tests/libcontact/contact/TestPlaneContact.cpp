// A grain against a rigid plane: the static force law and an elastic bounce.
#include "lsdem/contact/NormalModel.h"
#include "lsdem/contact/PlaneContact.h"
#include "lsdem/core/Constants.h"
#include "lsdem/simulation/RigidBody.h"
#include "lsdem/ls/Bake.h"

#include <gtest/gtest.h>

using namespace lsdem;

namespace {

const GrainAsset& ballAsset()
{
    static const GrainAsset asset = [] {
        BakeOptions o;
        o.voxelSize = 0.05;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 8000;
        std::vector<std::string> warnings;
        return bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings);
    }();
    return asset;
}

/// Total adapted force and torque on the grain from the plane.
void planeForce(const GrainAsset& a, const RigidPose& pose, const Plane& plane, double kStar,
                Vec3& force, Vec3& torque)
{
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findPlaneContacts(a, pose, plane, contacts, stats);
    std::vector<PointForce> forces;
    normalModel(Formulation::Adapted).forces(contacts, kStar, 1.0, forces);
    force = torque = Vec3::Zero();
    for (const PointForce& f : forces) {
        force += f.force;
        torque += (f.point - pose.position).cross(f.force);
    }
}

} // namespace

// A sphere pressed into a plane by δ: the cap behind the plane has depth δ - R(1 - cos θ) and
// the traction acts along the plane's normal, so the adapted force tends to exactly
// kn*·∫ d dA = kn*·π·R·δ² (about twice the sphere–sphere value, whose cap is half as deep).
TEST(PlaneContact, SpherePressedIntoAPlaneGivesTheCapIntegral)
{
    const GrainAsset& a = ballAsset();
    const Plane floor;  // z = 0, normal +z
    for (double delta : {0.05, 0.1}) {
        RigidPose pose;
        pose.position = Vec3(0, 0, 5.0 - delta);
        pose.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
        Vec3 force, torque;
        planeForce(a, pose, floor, 1e3, force, torque);
        // With u = cos θ from the bottom, d = δ - R(1 - u) for u > 1 - δ/R and dA = 2πR² du:
        // P = kn*·2πR²·∫ (δ - R + R u) du = kn*·π·R·δ².
        const double exact = 1e3 * kPi * 5.0 * delta * delta;
        EXPECT_NEAR(force.z() / exact, 1.0, 0.02) << delta;  // node quadrature at N = 8000
        EXPECT_NEAR(force.x(), 0.0, 1e-12 * exact);           // the plane pushes along its normal
        EXPECT_LT(torque.norm(), 0.02 * exact * 5.0);
    }
}

// No gravity, no damping: an elastic sphere hits the plane and leaves with its impact speed
// (the contact force is conservative; velocity Verlet keeps the energy to O(dt²)).
TEST(PlaneContact, ElasticSphereReboundsWithItsImpactSpeed)
{
    const GrainAsset& a = ballAsset();
    const Plane floor;
    RigidBody ball;
    const double density = 7.85e-9;  // tonne/mm³ (steel), so forces are in N
    ball.mass = density * a.mass.volume;
    ball.principalInertia = density * a.mass.inertia.diagonal();
    ball.pose.position = Vec3(0, 0, 5.0 + 0.01);
    const double impactSpeed = 100.0;  // mm/s
    ball.velocity = Vec3(0, 0, -impactSpeed);
    // Contact time scale: P = π k R δ² is a nonlinear spring; at the peak the stiffness
    // 2π k R δ_max with δ_max from ½mv² = π k R δ³/3; dt = a small fraction of sqrt(m/k_eff).
    const double kStar = 1e3;
    const double deltaMax = std::cbrt(1.5 * ball.mass * impactSpeed * impactSpeed /
                                      (kPi * kStar * 5.0));
    const double stiffness = 2 * kPi * kStar * 5.0 * deltaMax;
    const double dt = 0.02 * std::sqrt(ball.mass / stiffness);
    Vec3 force, torque;
    planeForce(a, ball.pose, floor, kStar, force, torque);
    double deepest = 0.0;
    int step = 0;
    for (; step < 200000 && !(ball.velocity.z() > 0 && ball.pose.position.z() > 5.01);
         ++step) {
        kick(ball, force, torque, 0.5 * dt);
        drift(ball, dt);
        planeForce(a, ball.pose, floor, kStar, force, torque);
        kick(ball, force, torque, 0.5 * dt);
        deepest = std::max(deepest, 5.0 - ball.pose.position.z());
    }
    ASSERT_GT(ball.velocity.z(), 0.0) << "the ball never came back";
    // The contact was resolved: it lasted many steps and reached the predicted depth.
    EXPECT_GT(step, 100);
    EXPECT_NEAR(deepest / deltaMax, 1.0, 0.05);
    EXPECT_NEAR(ball.velocity.z() / impactSpeed, 1.0, 0.005);
}

// Skipping node blocks wholly in front of the plane must not lose a single contact: the same
// nodes, in the same order, as testing every node, for tilted planes cutting the sphere at
// several depths, and most nodes culled when the contact is small.
TEST(PlaneContact, BlockCullingFindsExactlyTheContactsOfTheFullScan)
{
    const GrainAsset& withBlocks = ballAsset();
    ASSERT_FALSE(withBlocks.nodeBlocks.empty());
    GrainAsset everyNode = withBlocks;
    everyNode.nodeBlocks.clear();
    RigidPose pose;
    pose.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    for (double depth : {0.01, 0.3, 2.0, 6.0}) {
        Plane plane;
        plane.normal = Vec3(0.3, -0.2, 1.0).normalized();
        plane.point = pose.position - (5.0 - depth) * plane.normal;
        std::vector<NodeContact> culled, full;
        NodeCheckStats culledStats, fullStats;
        findPlaneContacts(withBlocks, pose, plane, culled, culledStats);
        findPlaneContacts(everyNode, pose, plane, full, fullStats);
        ASSERT_EQ(culled.size(), full.size()) << "depth " << depth;
        ASSERT_GT(full.size(), 0u);
        for (size_t k = 0; k < full.size(); ++k) {
            EXPECT_EQ(culled[k].node, full[k].node);
            EXPECT_EQ(culled[k].depth, full[k].depth);
        }
        if (depth < 0.5) {
            EXPECT_GT(culledStats.nodesCulled, static_cast<long long>(withBlocks.nodes.size() / 2));
        }
    }
}
