// The narrow phase (findNodeContacts): depth, normal and contact point of a box's nodes inside
// a sphere's level set against the exact sphere distance; the culling counters; node blocks
// against a plain scan; node order; and the refusal of node blocks that no longer fit the nodes.
#include "lsdem/contact/NodeContact.h"
#include "lsdem/ls/Bake.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <set>
#include <stdexcept>

using namespace lsdem;

namespace {

constexpr double kRadius = 1.0;  // grain B, a sphere
constexpr double kVoxel = 0.05;  // B's voxels

/// Grain B: a sphere of radius 1 baked at 0.05 (its nodes do not matter here: coarse).
const GrainAsset& sphereB()
{
    static const GrainAsset asset = [] {
        BakeOptions o;
        o.voxelSize = kVoxel;
        o.nodeSpacing = 0.5;
        std::vector<std::string> warnings;
        return bakeAnalytic(AnalyticShape::sphere(kRadius), o, warnings);
    }();
    return asset;
}

/// Grain A: a unit cube with structured face grids of spacing 0.1 (~600 nodes).
const GrainAsset& cubeA()
{
    static const GrainAsset asset = [] {
        BakeOptions o;
        o.voxelSize = 0.1;
        o.nodeSpacing = 0.1;
        std::vector<std::string> warnings;
        return bakeAnalytic(AnalyticShape::box(1.0, 1.0, 1.0), o, warnings);
    }();
    return asset;
}

/// A pose of the cube with one corner deep in the sphere and its faces cutting it at angles.
RigidPose cubePose()
{
    RigidPose p;
    p.position = Vec3(0.95, 0.35, -0.25);
    p.orientation = Quat(Eigen::AngleAxisd(0.6, Vec3(1, -2, 0.5).normalized()));
    return p;
}

RigidPose spherePose()
{
    RigidPose p;
    p.position = Vec3(0.1, -0.05, 0.02);
    p.orientation = Quat(Eigen::AngleAxisd(1.1, Vec3(0.3, 1, 2).normalized()));
    return p;
}

} // namespace

// φ_B is the exact distance |x| - R sampled at the voxels, then interpolated trilinearly. For a
// function with a positive semi-definite Hessian the trilinear error is at most
// (h²/8)·(φ_xx + φ_yy + φ_zz) = (h²/8)·(2/r) over the cell, r ≥ |x| - √3·h; float storage adds
// ~6e-8·R. Each gradient component is the cell's difference quotient, off by at most
// (h/2)·φ_ii ≤ h/(2r) with Σ(1 - n_i²) = 2, so |Δ∇φ| ≤ h/(√2·r) to first order: we allow h/r.
TEST(NodeContact, DepthNormalAndPointMatchTheExactSphereWithinInterpolationError)
{
    const GrainAsset& a = cubeA();
    const GrainAsset& b = sphereB();
    const RigidPose poseA = cubePose(), poseB = spherePose();
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findNodeContacts(a, poseA, b, poseB, contacts, stats);
    ASSERT_GT(contacts.size(), 30u);

    std::set<int> found;
    double deepest = 0.0;
    for (const NodeContact& c : contacts) {
        found.insert(c.node);
        const Vec3 x = poseA.toWorld(a.nodes.positions[c.node]);
        const Vec3 offset = x - poseB.position;
        const double r = offset.norm();
        const double cellR = r - std::sqrt(3.0) * kVoxel;
        ASSERT_GT(cellR, 0.1) << "node too close to the centre for the bound";
        const double depthTol = kVoxel * kVoxel / (4 * cellR) + 1e-7;
        const double normalTol = kVoxel / cellR;
        const double exactDepth = kRadius - r;
        const Vec3 exactNormal = offset / r;
        EXPECT_NEAR(c.depth, exactDepth, depthTol) << "node " << c.node;
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_LT((c.normal - exactNormal).norm(), normalTol) << "node " << c.node;
        // The contact point is the node moved half its depth along the normal (identity), and
        // so within the same errors of the exact one.
        EXPECT_LT((c.point - (x + 0.5 * c.depth * c.normal)).norm(), 1e-12);
        EXPECT_LT((c.point - (x + 0.5 * exactDepth * exactNormal)).norm(),
                  0.5 * depthTol + 0.5 * c.depth * normalTol);
        EXPECT_EQ(c.area, a.nodes.areas[c.node]);
        deepest = std::max(deepest, c.depth);
    }
    EXPECT_GT(deepest, 0.3);  // the pose does test deep nodes, not just a graze

    // Completeness: every node clearly inside (beyond the depth error) was found, and none
    // clearly outside was.
    for (size_t i = 0; i < a.nodes.size(); ++i) {
        const double r = (poseA.toWorld(a.nodes.positions[i]) - poseB.position).norm();
        const double tol = kVoxel * kVoxel / (4 * std::max(r - std::sqrt(3.0) * kVoxel, 0.1));
        if (kRadius - r > tol + 1e-7) {
            EXPECT_TRUE(found.count(int(i))) << "missed node " << i;
        }
        if (kRadius - r < -tol - 1e-7) {
            EXPECT_FALSE(found.count(int(i))) << "extra node " << i;
        }
    }
}

TEST(NodeContact, CountersAddUpAndResultsAreAppendedInNodeOrder)
{
    const GrainAsset& a = cubeA();
    const GrainAsset& b = sphereB();
    std::vector<NodeContact> contacts(3);  // findNodeContacts appends: keep what is there
    NodeCheckStats stats;
    stats.nodesConsidered = 7;  // and adds to the counters
    findNodeContacts(a, cubePose(), b, spherePose(), contacts, stats);
    const long long n = static_cast<long long>(a.nodes.size());
    EXPECT_EQ(stats.nodesConsidered, 7 + n);
    EXPECT_EQ(stats.nodesCulled + stats.nodesSampled, n);
    EXPECT_GT(stats.nodesCulled, 0);  // the far side of the cube is outside B's sphere
    EXPECT_EQ(stats.nodesInContact, static_cast<long long>(contacts.size()) - 3);
    EXPECT_LE(stats.nodesInContact, stats.nodesSampled);
    for (size_t k = 4; k < contacts.size(); ++k)
        EXPECT_LT(contacts[k - 1].node, contacts[k].node) << "node order";

    // Grains whose bounding spheres are apart: every node culled, none sampled.
    RigidPose far = cubePose();
    far.position.x() += a.boundingRadius + b.boundingRadius;
    NodeCheckStats farStats;
    std::vector<NodeContact> none;
    findNodeContacts(a, far, b, spherePose(), none, farStats);
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(farStats.nodesConsidered, n);
    EXPECT_EQ(farStats.nodesCulled, n);
    EXPECT_EQ(farStats.nodesSampled, 0);
}

// Blocks only skip work: the same contacts, bit for bit and in the same order, as a scan of
// every node, for poses from a graze to a deep overlap; and at least as many nodes culled.
TEST(NodeContact, NodeBlocksGiveExactlyTheContactsOfThePlainScan)
{
    const GrainAsset& withBlocks = cubeA();
    ASSERT_GT(withBlocks.nodeBlocks.clusters.size(), 1u);
    GrainAsset plain = withBlocks;
    plain.nodeBlocks.clear();
    const GrainAsset& b = sphereB();
    for (double shift : {0.0, 0.3, 0.6, 0.75}) {
        RigidPose poseA = cubePose();
        poseA.position.x() += shift;
        std::vector<NodeContact> blocked, scanned;
        NodeCheckStats blockedStats, scannedStats;
        findNodeContacts(withBlocks, poseA, b, spherePose(), blocked, blockedStats);
        findNodeContacts(plain, poseA, b, spherePose(), scanned, scannedStats);
        ASSERT_EQ(blocked.size(), scanned.size()) << "shift " << shift;
        for (size_t k = 0; k < scanned.size(); ++k) {
            EXPECT_EQ(blocked[k].node, scanned[k].node);
            EXPECT_EQ(blocked[k].depth, scanned[k].depth);
            EXPECT_EQ(blocked[k].normal, scanned[k].normal);
            EXPECT_EQ(blocked[k].point, scanned[k].point);
            EXPECT_EQ(blocked[k].area, scanned[k].area);
        }
        EXPECT_GE(blockedStats.nodesCulled, scannedStats.nodesCulled);
        EXPECT_EQ(blockedStats.nodesInContact, scannedStats.nodesInContact);
        EXPECT_EQ(blockedStats.nodesCulled + blockedStats.nodesSampled,
                  static_cast<long long>(plain.nodes.size()));
    }
}

// Blocks made for other nodes would drop contacts silently: a node removed without regrouping
// is a logic error, not a wrong answer.
TEST(NodeContact, NodeBlocksThatDoNotMatchTheNodesAreRefused)
{
    GrainAsset a = cubeA();
    a.nodes.positions.pop_back();
    a.nodes.normals.pop_back();
    a.nodes.areas.pop_back();
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    EXPECT_THROW(findNodeContacts(a, cubePose(), sphereB(), spherePose(), contacts, stats),
                 std::logic_error);
    a.nodeBlocks = groupNodesIntoBlocks(a.nodes);
    EXPECT_NO_THROW(findNodeContacts(a, cubePose(), sphereB(), spherePose(), contacts, stats));
    EXPECT_FALSE(contacts.empty());
}
