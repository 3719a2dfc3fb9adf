#include "lsdem/contact/NodeContact.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace lsdem {

namespace {

/// Remove the nodes @a nodes (ascending, each in one of the runs) from the runs [begin, end)
/// of @a runs (ascending), splitting a run where a node leaves its middle. The runs are built
/// in this thread's buffer and copied back, so a pair allocates only when its runs outgrow
/// what it holds.
void leaveOut(std::vector<std::pair<int, int>>& runs, const std::vector<int>& nodes)
{
    thread_local std::vector<std::pair<int, int>> kept;
    kept.clear();
    size_t k = 0;
    for (auto [begin, end] : runs) {
        for (; k < nodes.size() && nodes[k] < end; ++k) {
            if (nodes[k] > begin) kept.emplace_back(begin, nodes[k]);
            begin = nodes[k] + 1;
        }
        if (begin < end) kept.emplace_back(begin, end);
    }
    runs.assign(kept.begin(), kept.end());
}

/// Remove from @a cells (ascending by node) those of the nodes @a nodes (ascending).
void leaveOut(std::vector<CandidateBlocks::SampledCell>& cells, const std::vector<int>& nodes)
{
    size_t kept = 0, k = 0;
    for (const CandidateBlocks::SampledCell& c : cells) {
        while (k < nodes.size() && nodes[k] < c.node) ++k;
        if (k < nodes.size() && nodes[k] == c.node) continue;
        cells[kept++] = c;
    }
    cells.resize(kept);
}

} // namespace

void findNodeContacts(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out,
                      NodeCheckStats& stats, CandidateBlocks* candidates)
{
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    // Whole-grain cull: bounding spheres apart means no node can be inside B.
    const double reachB = b.boundingRadius;
    if ((poseA.position - poseB.position).norm() > a.boundingRadius + reachB) {
        stats.nodesCulled += count;
        return;
    }
    // One rigid map from A's asset frame to B's: x_B = R x_A + t.
    const Quat toB = poseB.orientation.conjugate() * poseA.orientation;
    const Vec3 translation = poseB.orientation.conjugate() * (poseA.position - poseB.position);
    // Remembered blocks need blocks that match the nodes; without them every block is walked.
    const NodeBlocks& groups = a.nodeBlocks;
    if (candidates && (groups.empty() || !groups.matches(a.nodes.size()))) {
        candidates->valid = false;  // not trusted again should the blocks be regrouped later
        candidates = nullptr;
    }
    // A near pair found clear a few steps ago, and not moved enough since, is done here: most
    // near pairs of a settled heap, so this check comes before anything else is computed.
    const bool runsHold = candidates && candidates->holds(toB, translation, a.boundingRadius);
    if (runsHold && candidates->clearOfContact(toB, translation, a.boundingRadius)) {
        stats.nodesCulled += count;  // no node can have come into contact since it was clear
        return;
    }
    const Eigen::Matrix3d rotation = toB.toRotationMatrix();
    const Eigen::Matrix3d bToWorld = poseB.orientation.toRotationMatrix();
    const double reach2 = reachB * reachB;

    // Clusters and blocks of A's nodes are ruled out in two ways: their sphere misses B's
    // bounding sphere (tested in A's frame, where it costs no rotation), or it misses the box
    // outside which B's level set is never negative. Both keep a hair of slack for round-off:
    // a node they let through still meets the exact tests below, so they only save work.
    const Vec3 centerOfB = -(rotation.transpose() * translation);  // B's origin in A's frame
    const double slack = 1.0 + 1e-9;
    // With a margin m > 0 the test answers for every pose of A within m of this one.
    // A single node is a ball of radius 0.
    auto isBallClearWithin = [&](const Vec3& center, double radius, double m) {
        const double reach = (reachB + radius + m) * slack;
        if ((center - centerOfB).squaredNorm() > reach * reach) return true;
        const Vec3 c = rotation * center + translation;
        const Vec3 outside = (b.insideBoxMin - c).cwiseMax(0.0) + (c - b.insideBoxMax).cwiseMax(0.0);
        const double r = (radius + m) * slack;
        return outside.squaredNorm() > r * r;
    };
    auto isClearWithin = [&](const NodeBlock& run, double m) {
        return isBallClearWithin(run.center, run.radius, m);
    };

    // An unregistered accessor costs next to nothing, but only when some node gets near B.
    std::optional<LevelSetSampler> sampler;
    const Vec3* positions = a.nodes.positions.data();
    // With remembered candidates, each sampled node's cell from the last step is looked up by
    // walking the last step's cells alongside the nodes (both ascending); this step's are
    // gathered in this thread's buffer and copied in at the end.
    thread_local std::vector<CandidateBlocks::SampledCell> nextCells;
    const std::vector<CandidateBlocks::SampledCell>* lastCells = nullptr;
    size_t cursor = 0;
    auto samplerOfB = [&]() -> LevelSetSampler& {
        if (!sampler) sampler.emplace(*b.levelSet);
        return *sampler;
    };
    auto sampleNode = [&](int i, const Vec3& inB) {
        if (!lastCells) return samplerOfB().sample(inB);
        while (cursor < lastCells->size() && (*lastCells)[cursor].node < i) ++cursor;
        CandidateBlocks::SampledCell& next = nextCells.emplace_back();
        next.node = i;
        if (cursor < lastCells->size() && (*lastCells)[cursor].node == i)
            next.cell = (*lastCells)[cursor].cell;
        return samplerOfB().sample(inB, next.cell);
    };
    // How near the visited nodes came to contact, for CandidateBlocks::clearGap: the smallest
    // squared distance to B's centre of those outside its sphere, the smallest distance outside
    // the inside box along an axis, the smallest φ_B ≥ 0 sampled; and whether any φ_B < 0.
    double nearestOutsideSphere2 = std::numeric_limits<double>::infinity();
    double nearestOutsideBox = std::numeric_limits<double>::infinity();
    double smallestPhi = std::numeric_limits<double>::infinity();
    bool anyInside = false;
    // A node just outside B's sphere may be far from B's surface, but the sphere alone would
    // say it is a hair from contact: within this of the sphere, the gap takes φ_B there too
    // (sampled for the gap only; such a node is still culled). 0: no gap is kept.
    double sphereBand = 0.0;
    double nearestInBand = std::numeric_limits<double>::infinity();  // their gaps
    // When the remembered nodes are found afresh, a node sampled at φ_B above this cannot come
    // into contact while they hold (it moves less than the margin relative to B, and φ_B
    // changes by at most levelSetSlope per unit of distance): it is left out of them. The
    // slack covers round-off (φ_B and the move are computed, not exact). Infinite: none.
    double leaveOutAbove = std::numeric_limits<double>::infinity();
    std::vector<int>* leftOut = nullptr;  // such nodes, ascending (this thread's buffer)
    auto visit = [&](int begin, int end) {
        // Most nodes of a run lie outside B's bounding sphere. That test is made in A's frame
        // (a difference and a square, no rotation); only the nodes inside are carried to B's
        // frame. The loop's constants are copied to locals so they stay in registers; the map
        // to B's frame as twelve numbers: a copied Matrix3d is stored in 16-byte pieces and its
        // columns (24 bytes apart) read back across two of them, a stall on every call.
        const Vec3 sphereCentre = centerOfB;
        const double sphereReach2 = reach2;
        const double r00 = rotation(0, 0), r01 = rotation(0, 1), r02 = rotation(0, 2),
                     r10 = rotation(1, 0), r11 = rotation(1, 1), r12 = rotation(1, 2),
                     r20 = rotation(2, 0), r21 = rotation(2, 1), r22 = rotation(2, 2);
        const double t0 = translation.x(), t1 = translation.y(), t2 = translation.z();
        auto intoB = [&](const Vec3& p) {
            return Vec3(r00 * p.x() + r01 * p.y() + r02 * p.z() + t0,
                        r10 * p.x() + r11 * p.y() + r12 * p.z() + t1,
                        r20 * p.x() + r21 * p.y() + r22 * p.z() + t2);
        };
        const Vec3 boxMin = b.insideBoxMin, boxMax = b.insideBoxMax;
        long long culled = 0;
        double outsideSphere2 = nearestOutsideSphere2, outsideBox = nearestOutsideBox;
        const double bandReach = reachB + sphereBand, bandReach2 = bandReach * bandReach;
        // How far a point is outside the box of B's inside along an axis (≤ 0: in it).
        auto beyondBox = [&](const Vec3& inB) {
            return std::max((boxMin - inB).maxCoeff(), (inB - boxMax).maxCoeff());
        };
        for (int i = begin; i < end; ++i) {
            const Vec3& inA = positions[i];
            const double d2 = (inA - sphereCentre).squaredNorm();
            if (d2 > sphereReach2) {
                ++culled;  // outside B's sphere: φ_B > 0 there
                if (d2 > bandReach2) {
                    outsideSphere2 = std::min(outsideSphere2, d2);
                } else {  // near the sphere: its gap is the larger of the two bounds
                    const Vec3 inB = intoB(inA);
                    const double outside = beyondBox(inB);
                    const double fromSurface =
                        outside > 0.0 ? outside : samplerOfB().phi(inB) / b.levelSetSlope;
                    nearestInBand = std::min(
                        nearestInBand, std::max(std::sqrt(d2) - reachB, fromSurface));
                }
                continue;
            }
            const Vec3 inB = intoB(inA);
            const double outside = beyondBox(inB);
            if (outside > 0.0) {
                ++culled;  // outside the box where φ_B can be negative
                outsideBox = std::min(outsideBox, outside);
                continue;
            }
            ++stats.nodesSampled;
            const LevelSetSample s = sampleNode(i, inB);
            if (!(s.phi < 0.0)) {
                smallestPhi = std::min(smallestPhi, s.phi);  // (a NaN φ leaves it: see below)
                anyInside |= std::isnan(s.phi);
                if (s.phi > leaveOutAbove) leftOut->push_back(i);
                continue;
            }
            anyInside = true;
            const double gradientLength = s.gradient.norm();
            if (gradientLength == 0.0) continue;  // no direction to push (degenerate level set)
            ++stats.nodesInContact;
            NodeContact c;
            c.node = i;
            c.depth = -s.phi;
            c.normal = bToWorld * (s.gradient * (1.0 / gradientLength));  // one division
            const Vec3 nodeWorld = poseB.position + bToWorld * inB;
            c.point = nodeWorld + 0.5 * c.depth * c.normal;
            c.area = a.nodes.areas[i];
            out.push_back(c);
        }
        stats.nodesCulled += culled;
        nearestOutsideSphere2 = outsideSphere2;
        nearestOutsideBox = outsideBox;
    };
    if (!candidates) {
        forEachBlockNotClear(a, [&](const NodeBlock& run) { return isClearWithin(run, 0.0); },
                             visit, stats);
        return;
    }
    if (!runsHold) {
        // Walk every cluster and block with the margin, and remember the nodes let through.
        candidates->valid = true;
        candidates->rotation = toB;
        candidates->translation = translation;
        candidates->margin = CandidateBlocks::kMarginFraction * a.boundingRadius;
        candidates->runs.clear();
        const double m = candidates->margin;
        NodeCheckStats ignored;
        // Each node of a block let through is kept only if it too is within the margin of
        // B's sphere and box: most nodes of a block near B are not, and every step would
        // cull them again. Kept nodes that follow each other join into one run.
        std::vector<std::pair<int, int>>& runs = candidates->runs;
        forEachBlockNotClear(
            a, [&](const NodeBlock& run) { return isClearWithin(run, m); },
            [&](int begin, int end) {
                for (int i = begin; i < end; ++i) {
                    if (isBallClearWithin(positions[i], 0.0, m)) continue;
                    if (!runs.empty() && runs.back().second == i)
                        ++runs.back().second;
                    else
                        runs.emplace_back(i, i + 1);
                }
            },
            ignored);
    }
    // The remembered nodes, each tested as a full walk would; and how far from contact.
    sphereBand = candidates->wasClear ? candidates->margin : 0.0;
    nextCells.clear();
    lastCells = &candidates->cells;
    if (!runsHold) {
        thread_local std::vector<int> leftOutBuffer;
        leftOut = &leftOutBuffer;
        leftOut->clear();
        leaveOutAbove = b.levelSetSlope * candidates->margin * (1.0 + 1e-6) +
                        1e-9 * b.levelSet->voxelSize;
    }
    long long visited = 0;
    for (const auto& [begin, end] : candidates->runs) {
        visited += end - begin;
        visit(begin, end);
    }
    if (leftOut && !leftOut->empty()) {
        // Found afresh at this very map: the nodes sampled too far from B's surface to reach it
        // while the list holds leave the runs, and their cells the remembered ones.
        leaveOut(candidates->runs, *leftOut);
        leaveOut(nextCells, *leftOut);
    }
    // Copied, not swapped: a swap would hand this pair the thread's buffer, grown by the
    // largest pair it served, and thousands of pairs would each end up that large.
    candidates->cells.assign(nextCells.begin(), nextCells.end());
    stats.nodesCulled += count - visited;
    // No node in contact: each visited node is at least this far from coming into contact
    // (outside B's sphere, outside the box, or φ_B ≥ 0 with φ_B changing by at most
    // levelSetSlope per unit of distance), and the nodes outside the runs stay clear while
    // the runs hold. Until a node may have moved that far, this direction can be skipped.
    candidates->clearGap = 0.0;
    candidates->wasClear = !anyInside;
    if (!anyInside) {
        const double gap = std::min({std::sqrt(nearestOutsideSphere2) - reachB, nearestInBand,
                                     nearestOutsideBox, smallestPhi / b.levelSetSlope});
        if (gap > 0.0) {
            candidates->clearGap = gap;
            candidates->clearRotation = toB;
            candidates->clearTranslation = translation;
        }
    }
}

} // namespace lsdem
