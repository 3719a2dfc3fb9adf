// Remembered candidate blocks (CandidateBlocks.h): along a trajectory of small random moves
// and turns of grain A against grain B, the contacts found with the remembered list equal,
// node for node and bit for bit, those of a full walk; the list is reused over many steps and
// refreshed when A has moved by more than its margin.
#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/contact/NodeContact.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/ls/NodeShape.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <iostream>
#include <map>
#include <random>

using namespace lsdem;

namespace {

/// A bumpy grain with a few thousand nodes in Z-ordered blocks, baked coarsely.
const GrainAsset& grain(double halfLength)
{
    BakeOptions o;
    o.voxelSize = 0.08;
    o.nodeSpacing = 0.06;
    std::vector<std::string> warnings;
    static std::map<double, GrainAsset> assets;
    auto it = assets.find(halfLength);
    if (it == assets.end())
        it = assets.emplace(halfLength, bakeAnalytic(AnalyticShape::ellipsoid(halfLength, 1.0, 0.7),
                                                     o, warnings)).first;
    return it->second;
}

double uniform(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53 - 0.5; }

/// Whether the remembered list found the full walk's contacts: the same nodes in the same
/// order, bit for bit in depth, normal and point.
::testing::AssertionResult sameContacts(const std::vector<NodeContact>& full,
                                        const std::vector<NodeContact>& withList)
{
    if (full.size() != withList.size())
        return ::testing::AssertionFailure()
               << full.size() << " contacts by a full walk, " << withList.size() << " with the list";
    for (size_t k = 0; k < full.size(); ++k)
        if (full[k].node != withList[k].node || full[k].depth != withList[k].depth ||
            full[k].normal != withList[k].normal || full[k].point != withList[k].point)
            return ::testing::AssertionFailure() << "contact " << k << " (node " << full[k].node
                                                 << ") differs";
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(CandidateBlocks, SameContactsAsAFullWalkAlongARandomTrajectory)
{
    const GrainAsset& a = grain(1.4);
    const GrainAsset& b = grain(1.0);
    ASSERT_FALSE(a.nodeBlocks.empty());
    RigidPose poseA, poseB;
    poseA.position = Vec3(2.2, 0.1, 0.0);  // overlapping B by about 0.2 along x
    poseB.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(0, 0, 1)));
    std::mt19937_64 rng(11);
    CandidateBlocks remembered;
    LevelSetSampler sampler(*b.levelSet);
    int refreshes = 0, steps = 400, stepsInContact = 0;
    long long leftOutFarFromB = 0, sampledByList = 0, sampledByWalk = 0;
    for (int step = 0; step < steps; ++step) {
        // Steps of up to 1 % of A's bounding radius and 0.6° per axis: the list (margin 2 %)
        // lasts a few steps, then must be refreshed.
        poseA.position += 0.01 * a.boundingRadius * Vec3(uniform(rng), uniform(rng), uniform(rng));
        poseA.position.x() = std::clamp(poseA.position.x(), 1.9, 2.5);
        poseA.orientation = (Quat(Eigen::AngleAxisd(0.02 * uniform(rng), Vec3::UnitX())) *
                             Quat(Eigen::AngleAxisd(0.02 * uniform(rng), Vec3::UnitY())) *
                             poseA.orientation).normalized();
        std::vector<NodeContact> full, withList;
        NodeCheckStats fullStats, listStats;
        const bool wasValid = remembered.valid;
        const Quat before = remembered.rotation;
        findNodeContacts(a, poseA, b, poseB, full, fullStats);
        findNodeContacts(a, poseA, b, poseB, withList, listStats, &remembered);
        if (!wasValid || !remembered.rotation.coeffs().isApprox(before.coeffs(), 0.0)) ++refreshes;
        stepsInContact += full.empty() ? 0 : 1;
        ASSERT_TRUE(sameContacts(full, withList)) << "step " << step;
        // The counters add up the same way: every node is either culled or sampled (and the
        // list samples the same nodes, unless it knows A clear of B and samples none).
        EXPECT_EQ(listStats.nodesConsidered, fullStats.nodesConsidered);
        EXPECT_EQ(listStats.nodesCulled + listStats.nodesSampled,
                  fullStats.nodesCulled + fullStats.nodesSampled);
        // Only nodes within the margin of B's bounding sphere and of the box of its inside
        // are kept, not whole blocks.
        const double slack = 1.0 + 1e-9;
        const double keep = (b.boundingRadius + remembered.margin) * slack;
        for (const auto& [begin, end] : remembered.runs)
            for (int i = begin; i < end; ++i) {
                const Vec3 inB = remembered.rotation * a.nodes.positions[static_cast<size_t>(i)] +
                                 remembered.translation;
                ASSERT_LE(inB.norm(), keep) << "node " << i << ", step " << step;
                const Vec3 outside = (b.insideBoxMin - inB).cwiseMax(0.0) +
                                     (inB - b.insideBoxMax).cwiseMax(0.0);
                ASSERT_LE(outside.norm(), remembered.margin * slack) << "node " << i;
            }
        // And every node left out is beyond the margin of B's sphere or of that box, or was
        // sampled too far outside B to reach it within the margin (φ_B above the slope bound
        // times the margin, at the list's map): any other could come into contact while the
        // list holds, and no walk would see it.
        std::vector<bool> kept(a.nodes.size(), false);
        for (const auto& [begin, end] : remembered.runs)
            for (int i = begin; i < end; ++i) kept[static_cast<size_t>(i)] = true;
        const double loose = 1.0 - 1e-9;
        for (size_t i = 0; i < a.nodes.size(); ++i) {
            if (kept[i]) continue;
            const Vec3 inB = remembered.rotation * a.nodes.positions[i] + remembered.translation;
            const Vec3 outside = (b.insideBoxMin - inB).cwiseMax(0.0) +
                                 (inB - b.insideBoxMax).cwiseMax(0.0);
            if (inB.norm() > (b.boundingRadius + remembered.margin) * loose ||
                outside.norm() > remembered.margin * loose)
                continue;
            ASSERT_GT(sampler.phi(inB), b.levelSetSlope * remembered.margin * loose)
                << "node " << i << " left out, step " << step;
            ++leftOutFarFromB;
        }
        // The list samples no node that a full walk does not, and nodes left out for φ_B only
        // at the steps that found it afresh; each sampled node it keeps leaves its cell.
        EXPECT_LE(listStats.nodesSampled, fullStats.nodesSampled);
        EXPECT_LE(static_cast<long long>(remembered.cells.size()),
                  listStats.nodesSampled + listStats.nodesPassedOver);
        EXPECT_LE(listStats.nodesPassedOver, listStats.nodesCulled);
        for (const CandidateBlocks::SampledCell& c : remembered.cells)
            ASSERT_TRUE(kept[static_cast<size_t>(c.node)]) << "cell of node " << c.node;
        sampledByList += listStats.nodesSampled;
        sampledByWalk += fullStats.nodesSampled;
    }
    EXPECT_GT(stepsInContact, steps * 9 / 10);  // the trajectory stays in contact
    EXPECT_GT(refreshes, 5);                    // the list had to follow the motion
    EXPECT_LT(refreshes, steps / 2);            // and was reused most of the time
    // Nodes near B's sphere and box but far from its surface were left out, and sampled less.
    EXPECT_GT(leftOutFarFromB, 0);
    EXPECT_LT(sampledByList, sampledByWalk);
    std::cout << "[ measured ] nodes sampled along the trajectory: " << sampledByList
              << " with the list, " << sampledByWalk << " by full walks\n";
}

// A pressed into B and moved to and fro along the line of their centres by 0.4 of the list's
// margin (so the list holds throughout), with a slight wobble: a node sampled clear of B is
// passed over while it cannot have reached B, which must allow for the way A has moved since
// it was sampled (to and fro: the node may have come back towards B by twice the amplitude).
// The contacts equal a full walk's at every step, and nodes are passed over; with points and
// with patch quadrature (whose nodes touch B from a reach away).
TEST(CandidateBlocks, PassesOverANodeSampledClearOnlyWhileItCannotHaveReachedB)
{
    // Point contacts, and patch quadrature (a node reaches B from its patch's reach away).
    for (const bool patches : {false, true}) {
        SCOPED_TRACE(patches ? "patches" : "points");
        static const GrainAsset shapedA = withNodeShapes(grain(1.4));
        static const GrainAsset shapedB = withNodeShapes(grain(1.0));
        const GrainAsset& a = patches ? shapedA : grain(1.4);
        const GrainAsset& b = patches ? shapedB : grain(1.0);
        RigidPose poseA, poseB;
        const Vec3 centre(2.25, 0.05, 0.0);  // A overlaps B by about 0.15 along x
        poseB.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(0, 0, 1)));
        CandidateBlocks remembered;
        const double margin = CandidateBlocks::kMarginFraction * a.boundingRadius;
        // How far from B a node's patch may reach into it (NodeContact.cpp): its own reach at
        // B's steepest slope, and B's surface bending towards it.
        const double slope = std::max(1.0, b.levelSetSlope);
        const double reach = patches ? a.patchReach * slope + a.patchReach * a.patchReach *
                                                                  slope * b.patchConcavity
                                     : 0.0;
        LevelSetSampler sampler(*b.levelSet);
        long long passedOver = 0, sampledByList = 0, sampledByWalk = 0, contactNodes = 0;
        for (int step = 0; step < 240; ++step) {
            const double phase = 2.0 * M_PI * step / 37.0;
            poseA.position = centre - 0.4 * margin * std::sin(phase) * Vec3::UnitX();
            poseA.orientation = Quat(Eigen::AngleAxisd(1e-3 * std::sin(1.7 * phase), Vec3::UnitY()));
            // Every remembered node the list is about to pass over is at least its reach from
            // B at this pose: it could not have touched B.
            const Quat toB = poseB.orientation.conjugate() * poseA.orientation;
            const Vec3 shift = poseB.orientation.conjugate() * (poseA.position - poseB.position);
            const double move = CandidateBlocks::largestMove(
                remembered.rotation, remembered.translation, toB, shift, a.boundingRadius);
            if (remembered.valid && move < remembered.margin)
                for (const CandidateBlocks::SampledCell& c : remembered.cells) {
                    if (!(move < c.clearUntil)) continue;
                    const Vec3 inB = toB * a.nodes.positions[static_cast<size_t>(c.node)] + shift;
                    ASSERT_GE(sampler.phi(inB), reach) << "node " << c.node << ", step " << step;
                }
            std::vector<NodeContact> full, withList;
            NodeCheckStats fullStats, listStats;
            findNodeContacts(a, poseA, b, poseB, full, fullStats, nullptr, patches);
            findNodeContacts(a, poseA, b, poseB, withList, listStats, &remembered, patches);
            ASSERT_TRUE(sameContacts(full, withList)) << "step " << step;
            EXPECT_EQ(listStats.nodesCulled + listStats.nodesSampled,
                      fullStats.nodesCulled + fullStats.nodesSampled);
            passedOver += listStats.nodesPassedOver;
            sampledByList += listStats.nodesSampled;
            sampledByWalk += fullStats.nodesSampled;
            contactNodes += static_cast<long long>(full.size());
        }
        EXPECT_GT(contactNodes, 0);
        EXPECT_GT(passedOver, 0);  // the to and fro is what is tested
        EXPECT_LT(sampledByList, sampledByWalk);
        std::cout << "[ measured ] to and fro (" << (patches ? "patches" : "points") << "): "
                  << sampledByList << " nodes sampled with the list (" << passedOver
                  << " passed over), " << sampledByWalk << " by full walks\n";
    }
}

// A flat box A held just above a flat box B, its bottom face outside the box of B's inside by
// less than the list's margin (and well inside B's bounding sphere): those nodes may touch B
// after a move smaller than the margin, so the list must keep every one of them.
TEST(CandidateBlocks, KeepsTheNodesJustOutsideTheBoxOfBsInside)
{
    BakeOptions o;
    o.voxelSize = 0.08;
    o.nodeSpacing = 0.1;
    std::vector<std::string> warnings;
    const GrainAsset slab = bakeAnalytic(AnalyticShape::box(2.0, 2.0, 0.8), o, warnings);
    RigidPose poseA, poseB;
    CandidateBlocks remembered;
    const double margin = CandidateBlocks::kMarginFraction * slab.boundingRadius;
    // A's bottom face (z = −0.4 in A) half a margin above the top of B's inside box.
    poseA.position = Vec3(0, 0, slab.insideBoxMax.z() + 0.4 + 0.5 * margin);
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findNodeContacts(slab, poseA, slab, poseB, contacts, stats, &remembered);
    EXPECT_TRUE(contacts.empty());
    ASSERT_TRUE(remembered.valid);
    std::vector<bool> kept(slab.nodes.size(), false);
    for (const auto& [begin, end] : remembered.runs)
        for (int i = begin; i < end; ++i) kept[static_cast<size_t>(i)] = true;
    int bottomNodes = 0;
    for (size_t i = 0; i < slab.nodes.size(); ++i) {
        if (slab.nodes.positions[i].z() > -0.4 + 1e-9) continue;  // A's bottom face only
        ++bottomNodes;
        EXPECT_TRUE(kept[i]) << "bottom node " << i << " left out";
    }
    EXPECT_GT(bottomNodes, 100);
}

// A grain without node blocks cannot remember any: the list is walked in full every step and
// marked not valid, so it is not trusted should blocks be made later.
TEST(CandidateBlocks, WithoutNodeBlocksEveryStepIsAFullWalk)
{
    GrainAsset a = grain(1.4);
    a.nodeBlocks = NodeBlocks();
    const GrainAsset& b = grain(1.0);
    RigidPose poseA, poseB;
    poseA.position = Vec3(2.2, 0.1, 0.0);
    CandidateBlocks remembered;
    remembered.valid = true;  // as if left from earlier blocks
    std::vector<NodeContact> full, withList;
    NodeCheckStats fullStats, listStats;
    findNodeContacts(a, poseA, b, poseB, full, fullStats);
    findNodeContacts(a, poseA, b, poseB, withList, listStats, &remembered);
    ASSERT_FALSE(full.empty());
    ASSERT_EQ(full.size(), withList.size());
    for (size_t k = 0; k < full.size(); ++k) EXPECT_EQ(full[k].node, withList[k].node);
    EXPECT_EQ(listStats.nodesSampled, fullStats.nodesSampled);
    EXPECT_FALSE(remembered.valid);
}

// Two equal grains, A coming at B along the diagonal of their x-z planes (there the surface is
// 0.81 from the centre, the bounding sphere 1.0 and the box of the inside further still, so
// A's nodes are sampled long before contact) from a gap of 0.12 in small steps with small
// turns, until the two overlap by 0.06: while A is clear of B the list skips it once it knows
// how far every node is from
// contact (outside B's sphere, its inside box, or at φ_B ≥ g with φ_B's slope bounded), and
// samples again before any node could have crossed that distance. The contacts equal a full
// walk's at every step, the first contact included.
TEST(CandidateBlocks, SkipsAClearPairOnlyUntilANodeCouldReachContact)
{
    const GrainAsset& a = grain(1.0);
    const GrainAsset& b = a;
    ASSERT_LT(b.levelSetSlope, 1.8);
    RigidPose poseA, poseB;
    // Symmetric about the midpoint: they touch when it is on the surface, 0.811 along u.
    const Vec3 u = Vec3(1.0, 0.0, 1.0).normalized();
    poseA.position = 1.742 * u;
    std::mt19937_64 rng(3);
    CandidateBlocks remembered;
    LevelSetSampler sampler(*b.levelSet);
    int skipped = 0, sampledWhileClear = 0, stepsInContact = 0, firstContact = -1;
    for (int step = 0; step < 1200; ++step) {
        poseA.position -= 0.00015 * u;
        poseA.position.y() += 0.0004 * uniform(rng);
        poseA.orientation = (Quat(Eigen::AngleAxisd(0.001 * uniform(rng), Vec3::UnitZ())) *
                             poseA.orientation).normalized();
        std::vector<NodeContact> full, withList;
        NodeCheckStats fullStats, listStats;
        findNodeContacts(a, poseA, b, poseB, full, fullStats);
        findNodeContacts(a, poseA, b, poseB, withList, listStats, &remembered);
        ASSERT_TRUE(sameContacts(full, withList)) << "step " << step;
        // The gap kept at this step's map is a lower bound on every remembered node's distance
        // to contact: for a node inside B's sphere and its inside box, φ_B over the slope bound
        // (also for nodes passed over rather than sampled, whose φ_B the walk bounded from an
        // earlier sample).
        const Quat toB = poseB.orientation.conjugate() * poseA.orientation;
        const Vec3 shift = poseB.orientation.conjugate() * (poseA.position - poseB.position);
        if (remembered.clearGap > 0.0 && remembered.clearTranslation == shift) {
            for (const auto& [begin, end] : remembered.runs)
                for (int i = begin; i < end; ++i) {
                    const Vec3 inB = toB * a.nodes.positions[static_cast<size_t>(i)] + shift;
                    const Vec3 outside = (b.insideBoxMin - inB).cwiseMax(0.0) +
                                         (inB - b.insideBoxMax).cwiseMax(0.0);
                    if (inB.norm() > b.boundingRadius || outside.squaredNorm() > 0.0) continue;
                    ASSERT_GE(sampler.phi(inB) / b.levelSetSlope, remembered.clearGap * (1.0 - 1e-9))
                        << "node " << i << ", step " << step;
                }
        }
        if (!full.empty()) {
            ++stepsInContact;
            if (firstContact < 0) firstContact = step;
        } else if (fullStats.nodesSampled > 0) {
            (listStats.nodesSampled == 0 ? skipped : sampledWhileClear) += 1;
        }
    }
    EXPECT_GT(firstContact, 500);       // a long approach (0.12 at 0.00015 a step: ~800)
    EXPECT_GT(stepsInContact, 200);     // and then in contact
    EXPECT_GT(skipped, 300);            // about half the clear steps with nodes near B
    EXPECT_GT(sampledWhileClear, 5);    // but sampled again as the gap closed
}

TEST(CandidateBlocks, HoldsOnlyWhileEveryNodeMovedLessThanTheMargin)
{
    CandidateBlocks c;
    EXPECT_FALSE(c.holds(Quat::Identity(), Vec3::Zero(), 1.0));  // never made
    c.valid = true;
    c.margin = 0.1;
    EXPECT_TRUE(c.holds(Quat::Identity(), Vec3(0.099, 0, 0), 1.0));
    EXPECT_FALSE(c.holds(Quat::Identity(), Vec3(0.101, 0, 0), 1.0));
    // A turn by θ moves a node at distance r by 2 r sin(θ/2): 0.0999 for θ = 0.1, r = 1.
    const Quat turn(Eigen::AngleAxisd(0.1, Vec3::UnitZ()));
    EXPECT_TRUE(c.holds(turn, Vec3::Zero(), 1.0));
    EXPECT_FALSE(c.holds(turn, Vec3::Zero(), 1.002));
    EXPECT_FALSE(c.holds(turn, Vec3(0.001, 0, 0), 1.0));
}

// Nodes left out of the remembered runs (found in contact, so walked in full next time).
TEST(CandidateBlocks, NodesLeftOutSplitTheirRunsAndDropTheirCells)
{
    // Runs [0, 5) and [10, 12); leaving out 0 (a run's first), 2 (its middle), 4 (its last)
    // and 11 (the other's last) leaves [1, 2), [3, 4) and [10, 11).
    std::vector<std::pair<int, int>> runs{{0, 5}, {10, 12}};
    lsdem::leaveOutNodes(runs, {0, 2, 4, 11});
    const std::vector<std::pair<int, int>> expected{{1, 2}, {3, 4}, {10, 11}};
    EXPECT_EQ(runs, expected);

    std::vector<lsdem::CandidateBlocks::SampledCell> cells(5);
    for (int k = 0; k < 5; ++k) cells[size_t(k)].node = 2 * k;  // nodes 0, 2, 4, 6, 8
    lsdem::leaveOutNodes(cells, {1, 2, 8});
    ASSERT_EQ(cells.size(), 3u);
    EXPECT_EQ(cells[0].node, 0);
    EXPECT_EQ(cells[1].node, 4);
    EXPECT_EQ(cells[2].node, 6);

    lsdem::leaveOutNodes(runs, {});  // nothing left out: unchanged
    EXPECT_EQ(runs, expected);
}
