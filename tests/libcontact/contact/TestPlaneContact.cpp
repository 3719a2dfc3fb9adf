// A grain against a rigid plane: the static force law and an elastic bounce; node blocks; and
// patch quadrature (PatchQuadrature.h) against the cap integral and a flat face.
#include "lsdem/contact/NormalModel.h"
#include "lsdem/contact/PlaneContact.h"
#include "lsdem/core/Constants.h"
#include "lsdem/simulation/RigidBody.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/ls/NodeShape.h"

#include <gtest/gtest.h>

#include <random>

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

/// The same ball with its node shapes, for patch quadrature.
const GrainAsset& shapedBallAsset()
{
    static const GrainAsset asset = withNodeShapes(ballAsset());
    return asset;
}

/// Σ area·depth over the grain's contacts with @a plane (the adapted force over kn*).
double cap(const GrainAsset& a, const RigidPose& pose, const Plane& plane, bool patches)
{
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findPlaneContacts(a, pose, plane, contacts, stats, patches);
    double sum = 0.0;
    for (const NodeContact& c : contacts) sum += c.area * c.depth;
    return sum;
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

// Patch quadrature against the same cap integral π·R·δ² (times kn*): where the cap is a few node
// spacings across or less (spacing ~0.2, cap radius √(2Rδ) = 0.22 to 1), the nodes as points
// see one to a few dozen depths and the force jumps as the ball turns; each patch integrates
// the depth over its patch (its Voronoi cell), so the force varies far less. Over 64 random
// turns at each δ, the RMS error with patches is below 0.3 of the nodes' (measured 0.11 to 0.18
// of it; the nodes' own 10 % at δ = 0.005 down to 0.4 % at 0.05; disks of the nodes' areas,
// as patches were before the cells, gave 0.37 to 0.75), at the narrowest cap below a quarter
// of it (0.12); and its mean, the bias, is within 1 % (measured ≤ 0.40 %).
TEST(PlaneContact, PatchesFollowTheCapIntegralMoreCloselyThanNodes)
{
    const GrainAsset& a = shapedBallAsset();
    ASSERT_EQ(a.nodeShapes.size(), a.nodes.size());
    const Plane floor;
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (double delta : {0.005, 0.01, 0.02, 0.05}) {
        const double exact = kPi * 5.0 * delta * delta;
        double nodeSquares = 0.0, patchSquares = 0.0, patchSum = 0.0;
        const int turns = 64;
        for (int k = 0; k < turns; ++k) {
            RigidPose pose;
            pose.position = Vec3(0, 0, 5.0 - delta);
            pose.orientation = Quat(Eigen::Vector4d(normal(rng), normal(rng), normal(rng),
                                                    normal(rng)).normalized());
            const double nodeError = cap(a, pose, floor, false) / exact - 1.0;
            const double patchError = cap(a, pose, floor, true) / exact - 1.0;
            nodeSquares += nodeError * nodeError;
            patchSquares += patchError * patchError;
            patchSum += patchError;
        }
        const double nodeRms = std::sqrt(nodeSquares / turns), patchRms = std::sqrt(patchSquares / turns);
        EXPECT_LT(patchRms, 0.3 * nodeRms) << "delta " << delta << ": patches " << patchRms;
        if (delta == 0.005) {
            EXPECT_LT(patchRms, 0.25 * nodeRms) << "patches " << patchRms << ", nodes " << nodeRms;
        }
        EXPECT_LT(std::abs(patchSum / turns), 0.01) << "delta " << delta;
    }
}

// A box's flat face pressed wholly into a plane by δ: every node of the face has a flat patch
// (exact distance: the face's curvature is nil, NodeShape.h) parallel to the plane, wholly in,
// so its integral is δ·(its patch's area). The patch has the shape of the node's Voronoi cell,
// the s × s square of the face grid, scaled to the node's own tributary area A = s² (as the
// rays' rule measures it: unscaled, the rule found 0.976·s²): the patches' total force is the
// nodes', k·A·δ each, to the precision of the extents, stored as floats (a relative 2⁻²⁴
// each, twice that in an area: 1.2e-7; 2.4e-7 allowed). A
// bounded plane narrower than the face takes its nodes only (none on the sides or edges, whose
// patches would reach the plane where their nodes do not). The nodes of a structured face
// grid of spacing s stand for s² each: the total is also δ·s²·(their count).
TEST(PlaneContact, FlatFacePressedWhollyInGivesTheSameForceWithPatchesAsWithNodes)
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.2;
    std::vector<std::string> warnings;
    const AnalyticShape box = AnalyticShape::box(2.0, 1.6, 1.2);
    const GrainAsset a =
        withNodeShapes(withExactDistance(bakeAnalytic(box, o, warnings), box.exactDistance()));
    Plane floor;
    floor.halfU = floor.halfV = 0.5;  // within the face however it turns about z
    for (double delta : {0.01, 0.05}) {
        RigidPose pose;
        pose.position = Vec3(0.02, -0.03, 0.6 - delta);
        pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
        std::vector<NodeContact> nodes, patches;
        NodeCheckStats stats;
        findPlaneContacts(a, pose, floor, nodes, stats, false);
        findPlaneContacts(a, pose, floor, patches, stats, true);
        ASSERT_EQ(nodes.size(), patches.size()) << delta;
        ASSERT_GT(nodes.size(), 20u);
        // Contact by contact: the worst relative difference of k·area·depth (one line on failure).
        double nodeTotal = 0.0, patchTotal = 0.0, worst = 0.0;
        for (size_t k = 0; k < nodes.size(); ++k) {
            ASSERT_EQ(nodes[k].node, patches[k].node);
            const double node = nodes[k].area * nodes[k].depth;
            const double patch = patches[k].area * patches[k].depth;
            worst = std::max(worst, std::abs(patch / node - 1.0));
            EXPECT_NEAR(patches[k].depth, delta, 1e-14);
            EXPECT_LT((patches[k].point - nodes[k].point).norm(), 1e-14);
            EXPECT_EQ(patches[k].normal, nodes[k].normal);
            nodeTotal += node;
            patchTotal += patch;
        }
        EXPECT_LT(worst, 2.4e-7) << "delta " << delta;
        EXPECT_NEAR(patchTotal, nodeTotal, 2.4e-7 * nodeTotal) << delta;
        EXPECT_NEAR(nodeTotal, delta * 0.04 * double(nodes.size()), 1e-12 * nodeTotal) << delta;
    }
}

// The cap narrower than a node spacing: the setup of the slide-to-roll check, a ball of R 5 and
// 4000 nodes (spacing 0.28) from voxels of 0.1, resting on a floor by δ = 0.002 (its own weight
// at kn* = 1e3), a cap of radius √(2Rδ) = 0.14 spread over two to four patches. Each patch's
// depth there is set by its node's shape over distances of a node spacing, so the shape must
// be the surface's to far better than the overlap (a curvature error ε moves the depth at the
// patch's edge by ε·e²/2R ≈ ε·4 µm against δ = 2 µm): the voxels' shape (curvatures wrong by
// 13 % RMS node by node) gave an RMS error of 14 % over 64 turns (−31 % … +45 %), which an
// undamped rolling ball turned into hops of 30 µm. From the nodes' fitted jets the curvature
// errs by 0.3 %, and what is left is the rays' rule, which cuts each cell's corners or
// overshoots them by a few percent of its area (the same cells integrated exactly measured
// 0.4 % RMS, the rays 1.2 %): within 3 % RMS and a mean within 1 %.
TEST(PlaneContact, PatchesResolveACapNarrowerThanTheNodeSpacing)
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = 4000;
    std::vector<std::string> warnings;
    const GrainAsset a = withNodeShapes(bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings));
    const Plane floor;
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double delta = 0.002, exact = kPi * 5.0 * delta * delta;
    const int turns = 64;
    double squares = 0.0, sum = 0.0;
    for (int k = 0; k < turns; ++k) {
        RigidPose pose;
        pose.position = Vec3(0, 0, 5.0 - delta);
        pose.orientation = Quat(
            Eigen::Vector4d(normal(rng), normal(rng), normal(rng), normal(rng)).normalized());
        const double error = cap(a, pose, floor, true) / exact - 1.0;
        squares += error * error;
        sum += error;
    }
    EXPECT_LT(std::sqrt(squares / turns), 0.03);
    EXPECT_LT(std::abs(sum / turns), 0.01);
}
