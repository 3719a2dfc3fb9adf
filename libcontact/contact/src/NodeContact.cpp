#include "lsdem/contact/NodeContact.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/contact/PatchQuadrature.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace lsdem {

namespace {

/// One call of findNodeContacts: grain A's nodes against B's level set at one pose of the
/// pair, in phases. The whole grain, then clusters and blocks, then single nodes are culled
/// by B's bounding sphere and the box outside which φ_B ≥ 0; the nodes left are sampled. With
/// remembered candidates (CandidateBlocks.h) only their runs are walked, refreshed when they no
/// longer hold, and how far the pair is from contact is kept for the next call.
class NodeContactSearch
{
public:
    NodeContactSearch(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out, NodeCheckStats& stats,
                      bool patches)
        : mA(a), mB(b), mPoseA(poseA), mPoseB(poseB), mOut(out), mStats(stats),
          mPatches(patches), mReach(patches ? patchReach(a, b) : 0.0),
          mReachB(b.boundingRadius + mReach), mPerSlope(perSlope(b.levelSetSlope))
    {
        if (patches && a.nodeShapes.size() != a.nodes.size())
            throw std::logic_error("findNodeContacts: patch quadrature on an asset without node shapes");
    }

    void run(CandidateBlocks* candidates)
    {
        const long long count = static_cast<long long>(mA.nodes.size());
        mStats.nodesConsidered += count;
        // Whole-grain cull: bounding spheres apart means no node can be inside B.
        if ((mPoseA.position - mPoseB.position).norm() > mA.boundingRadius + mReachB) {
            mStats.nodesCulled += count;
            return;
        }
        // One rigid map from A's asset frame to B's: x_B = R x_A + t.
        mToB = mPoseB.orientation.conjugate() * mPoseA.orientation;
        mTranslation = mPoseB.orientation.conjugate() * (mPoseA.position - mPoseB.position);
        // Remembered blocks need blocks that match the nodes; without them every block is walked.
        const NodeBlocks& groups = mA.nodeBlocks;
        if (candidates && (groups.empty() || !groups.matches(mA.nodes.size()))) {
            candidates->valid = false;  // not trusted again should the blocks be regrouped later
            candidates = nullptr;
        }
        // A near pair found clear a few steps ago, and not moved enough since, is done here:
        // most near pairs of a settled heap, so this check comes before anything else.
        // (A's move since the runs' map is kept: passing over nodes uses it.)
        if (candidates && candidates->valid)
            mMove = candidates->moveSinceRuns(mToB, mTranslation, mA.boundingRadius);
        const bool runsHold = candidates && candidates->holdsAfter(mMove);
        if (runsHold && candidates->clearOfContact(mToB, mTranslation, mA.boundingRadius)) {
            mStats.nodesCulled += count;  // no node can have come into contact since it was clear
            return;
        }
        mRotation = mToB.toRotationMatrix();
        mBToWorld = mPoseB.orientation.toRotationMatrix();
        mCenterOfB = -(mRotation.transpose() * mTranslation);  // B's origin in A's frame
        if (!candidates) {
            forEachBlockNotClear(
                mA, [&](const NodeBlock& run) { return isClearWithin(run.center, run.radius, 0.0); },
                [&](int begin, int end) { visit(begin, end); }, mStats);
            return;
        }
        if (!runsHold) {
            rememberRuns(*candidates);
            mMove = 0.0;  // the runs' map is this one
        }
        visitRemembered(*candidates, runsHold);
        keepClearGap(*candidates);
    }

private:
    /// 1 / B's slope bound with a slack of 2e-6 for round-off (a product then stands for a
    /// division: the slack covers its rounding many times over); 0 for an unbounded slope, so
    /// that no node is passed over.
    static double perSlope(double slope)
    {
        return slope > 0.0 && std::isfinite(slope) ? 1.0 / (slope * (1.0 + 2e-6)) : 0.0;
    }

    /// How far from B a node of A may be and still have its patch touch B: A's patches' own
    /// reach (NodeShape.h) at B's steepest slope, and B's surface bending toward the patch by
    /// at most B's largest concavity at its nodes (twice it, for the bends between them).
    static double patchReach(const GrainAsset& a, const GrainAsset& b)
    {
        const double slope = std::isfinite(b.levelSetSlope) ? std::max(1.0, b.levelSetSlope) : 1.0;
        return a.patchReach * slope + a.patchReach * a.patchReach * slope * b.patchConcavity;
    }

    /// Whether a ball of A's frame (a cluster, a block; a node is a ball of radius 0) misses
    /// B's bounding sphere (tested in A's frame, where it costs no rotation) or the box outside
    /// which φ_B is never negative. With a margin m > 0 the answer holds for every pose of A
    /// within m of this one. Both tests keep a hair of slack for round-off: a node they let
    /// through still meets the exact tests of visit(), so they only save work.
    bool isClearWithin(const Vec3& center, double radius, double m) const
    {
        const double slack = 1.0 + 1e-9;
        const double reach = (mReachB + radius + m) * slack;
        if ((center - mCenterOfB).squaredNorm() > reach * reach) return true;
        const Vec3 c = mRotation * center + mTranslation;
        const Vec3 outside = (mB.insideBoxMin - c).cwiseMax(0.0) + (c - mB.insideBoxMax).cwiseMax(0.0);
        const double r = (radius + m + mReach) * slack;
        return outside.squaredNorm() > r * r;
    }

    /// An unregistered accessor costs next to nothing, but only when some node gets near B.
    LevelSetSampler& sampler()
    {
        if (!mSampler) mSampler.emplace(*mB.levelSet);
        return *mSampler;
    }

    /// Node @a i's entry among the last step's cells, if it has one: found by walking them
    /// alongside the nodes (both ascending).
    const CandidateBlocks::SampledCell* lastCellOf(int i)
    {
        const std::vector<CandidateBlocks::SampledCell>& last = *mLastCells;
        while (mCursor < last.size() && last[mCursor].node < i) ++mCursor;
        return mCursor < last.size() && last[mCursor].node == i ? &last[mCursor] : nullptr;
    }

    /// This step's entry for node @a i, about to be sampled, in this thread's buffer: its last
    /// cell (@a last's, if any), its clearUntil set once it is sampled. Its index, not its
    /// address: the buffer may grow before the node's batch is sampled.
    size_t keepCell(int i, const CandidateBlocks::SampledCell* last)
    {
        const size_t index = mNextCells->size();
        CandidateBlocks::SampledCell& next = mNextCells->emplace_back();
        next.node = i;
        if (last) next.cell = last->cell;
        return index;
    }

    /// A remembered node that cannot have reached B since it was sampled clear (its entry
    /// @a last): kept for the next step as it is, and how near it may now be to contact noted
    /// for keepClearGap, a bound: φ_B − reach ≥ slope·(clearUntil − move).
    void passOver(const CandidateBlocks::SampledCell& last)
    {
        mNextCells->push_back(last);
        ++mStats.nodesPassedOver;
        mSmallestPhi = std::min(mSmallestPhi, mB.levelSetSlope * (last.clearUntil - mMove));
    }

    /// The clearUntil of a node sampled clear of B at φ_B = @a phi (CandidateBlocks.h), with a
    /// slack for round-off (perSlope), and rounded down to a float; −1 (never passed over) when
    /// it is not positive, as when B's slope is unbounded.
    float clearUntilOf(double phi) const
    {
        const double until = (phi - mReach - 1e-9 * mB.levelSet->voxelSize) * mPerSlope - mMove;
        if (!(until > 0.0)) return -1.0f;  // NaN too
        float rounded = static_cast<float>(until);
        if (static_cast<double>(rounded) > until) rounded = std::nextafter(rounded, 0.0f);
        return rounded;
    }

    /// The nodes [begin, end): culled, sampled, and those with φ_B < 0 appended as contacts;
    /// how near the others came to contact is kept for keepClearGap.
    void visit(int begin, int end)
    {
        // Most nodes of a run lie outside B's bounding sphere. That test is made in A's frame
        // (a difference and a square, no rotation); only the nodes inside are carried to B's
        // frame. The loop's constants are copied to locals so they stay in registers; the map
        // to B's frame as twelve numbers: a copied Matrix3d is stored in 16-byte pieces and its
        // columns (24 bytes apart) read back across two of them, a stall on every call.
        const Vec3* positions = mA.nodes.positions.data();
        const Vec3 sphereCentre = mCenterOfB;
        const double reachB = mReachB, sphereReach2 = mReachB * mReachB;
        const double r00 = mRotation(0, 0), r01 = mRotation(0, 1), r02 = mRotation(0, 2),
                     r10 = mRotation(1, 0), r11 = mRotation(1, 1), r12 = mRotation(1, 2),
                     r20 = mRotation(2, 0), r21 = mRotation(2, 1), r22 = mRotation(2, 2);
        const double t0 = mTranslation.x(), t1 = mTranslation.y(), t2 = mTranslation.z();
        auto intoB = [&](const Vec3& p) {
            return Vec3(r00 * p.x() + r01 * p.y() + r02 * p.z() + t0,
                        r10 * p.x() + r11 * p.y() + r12 * p.z() + t1,
                        r20 * p.x() + r21 * p.y() + r22 * p.z() + t2);
        };
        const Vec3 boxMin = mB.insideBoxMin, boxMax = mB.insideBoxMax;
        long long culled = 0;
        double outsideSphere2 = mNearestOutsideSphere2, outsideBox = mNearestOutsideBox;
        const double bandReach = reachB + mSphereBand, bandReach2 = bandReach * bandReach;
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
                } else {
                    const Vec3 inB = intoB(inA);
                    noteGapInBand(inB, beyondBox(inB), std::sqrt(d2) - reachB);
                }
                continue;
            }
            const Vec3 inB = intoB(inA);
            const double outside = beyondBox(inB) - mReach;
            if (outside > 0.0) {
                ++culled;  // outside the box where φ_B can be negative (by more than the reach)
                outsideBox = std::min(outsideBox, outside);
                continue;
            }
            size_t cell = SampleBatch::kNoCell;
            if (mLastCells) {
                const CandidateBlocks::SampledCell* last = lastCellOf(i);
                if (last && mPassOver && mMove < last->clearUntil) {
                    ++culled;
                    passOver(*last);
                    continue;
                }
                cell = keepCell(i, last);
            }
            mBatch.node[mBatch.count] = i;
            mBatch.inB[mBatch.count] = inB;
            mBatch.cell[mBatch.count] = cell;
            if (++mBatch.count == SampleBatch::kSize) sampleBatch();
        }
        sampleBatch();
        mStats.nodesCulled += culled;
        mNearestOutsideSphere2 = outsideSphere2;
        mNearestOutsideBox = outsideBox;
    }

    /// The nodes let through the culls, waiting to be sampled. Sampling a batch in one loop,
    /// and only then acting on the samples, lets the CPU overlap one node's sample (a chain of
    /// dependent loads and arithmetic) with the next node's; node by node, each waited for the
    /// one before it. The order, and so every result, is the same.
    struct SampleBatch
    {
        static constexpr int kSize = 16;
        static constexpr size_t kNoCell = ~size_t(0);
        int count = 0;
        int node[kSize];
        Vec3 inB[kSize];    ///< the node in B's frame
        size_t cell[kSize];  ///< its entry in this step's cells (keepCell), or kNoCell
        // The samples, as plain arrays: an array of LevelSetSample would be zeroed every time
        // a search is made (once a pair and direction a step).
        double phi[kSize];
        Vec3 gradient[kSize];
    };

    /// Sample the batch's nodes, then keep those inside B as contacts (in node order).
    void sampleBatch()
    {
        const int count = mBatch.count;
        if (count == 0) return;
        mBatch.count = 0;
        mStats.nodesSampled += count;
        for (int k = 0; k < count; ++k) {
            const size_t cell = mBatch.cell[k];
            const LevelSetSample s = cell == SampleBatch::kNoCell
                                         ? sampler().sample(mBatch.inB[k])
                                         : sampler().sample(mBatch.inB[k], (*mNextCells)[cell].cell);
            mBatch.phi[k] = s.phi;
            mBatch.gradient[k] = s.gradient;
        }
        for (int k = 0; k < count; ++k) {
            const LevelSetSample s{mBatch.phi[k], mBatch.gradient[k]};
            const int i = mBatch.node[k];
            if (!(s.phi < mReach)) {
                noteClearNode(i, s.phi);
                if (mBatch.cell[k] != SampleBatch::kNoCell)
                    (*mNextCells)[mBatch.cell[k]].clearUntil = clearUntilOf(s.phi);
                continue;
            }
            mAnyInside = true;
            if (mPatches)
                addPatchContact(i, mBatch.inB[k], s);
            else
                addPointContact(i, mBatch.inB[k], s);
        }
    }

    /// A node of the band just outside B's bounding sphere (@a sphereGap from it, @a inB in B's
    /// frame, @a outside beyond the box of B's inside): its gap to B is the larger of the two
    /// bounds, the sphere's and the surface's, and the nearest such gap is kept.
    void noteGapInBand(const Vec3& inB, double outside, double sphereGap)
    {
        const double fromSurface = outside > 0.0
                                       ? outside - mReach
                                       : (sampler().phi(inB) - mReach) / mB.levelSetSlope;
        mNearestInBand = std::min(mNearestInBand, std::max(sphereGap, fromSurface));
    }

    /// A sampled node @a i clear of B (φ_B = @a phi, at least the reach): how near it came, and
    /// whether it is far enough to be left out of the remembered runs. (A NaN φ leaves the
    /// smallest as it was but counts as inside, so keepClearGap keeps no gap.)
    void noteClearNode(int i, double phi)
    {
        mSmallestPhi = std::min(mSmallestPhi, phi - mReach);
        mAnyInside |= std::isnan(phi);
        if (phi > mLeaveOutAbove + mReach) mLeftOut->push_back(i);
    }

    /// Node @a i, inside B (its φ and ∇φ @a s, at @a inB in B's frame), appended to the
    /// contacts as a point: depth −φ along ∇φ, acting halfway into the overlap.
    void addPointContact(int i, const Vec3& inB, const LevelSetSample& s)
    {
        const double gradientLength = s.gradient.norm();
        if (gradientLength == 0.0) return;  // no direction to push (degenerate level set)
        ++mStats.nodesInContact;
        NodeContact c;
        c.node = i;
        c.depth = -s.phi;
        c.normal = mBToWorld * (s.gradient * (1.0 / gradientLength));  // one division
        const Vec3 nodeWorld = mPoseB.position + mBToWorld * inB;
        c.point = nodeWorld + 0.5 * c.depth * c.normal;
        c.area = mA.nodes.areas[i];
        mOut.push_back(c);
    }

    /// Node @a i's patch against B (its φ and ∇φ at the node @a s, at @a inB in B's frame),
    /// appended to the contacts if any of it is in B. B's Hessian along the node's tangents is
    /// taken by central differences of ∇φ_B a voxel apart, only for a node whose patch may
    /// reach B.
    void addPatchContact(int i, const Vec3& inB, const LevelSetSample& s)
    {
        const double gradientLength = s.gradient.norm();
        if (gradientLength == 0.0) return;
        const NodeShape& shape = mA.nodeShapes[static_cast<size_t>(i)];
        // Out of reach whatever the patch's tilt: the depth grows by at most |∇φ| a unit of
        // distance over the patch, its own bend and B's (twice B's largest concavity).
        const double e = shape.reach;
        if (s.phi >= (e + shape.lift + e * e * mB.patchConcavity) * gradientLength) return;
        const PatchFrame frame = patchFrame(shape, mRotation);
        const double radius = shape.reach;
        const double h = mB.levelSet->voxelSize;
        // First without B's bend, allowing for the most B's concavity can take from C (twice
        // its largest at B's nodes, for the bends between them): a bound, so no Hessian is
        // sampled for a node whose patch cannot reach B.
        PatchDepth depth = patchDepth(frame, s.phi, s.gradient, 0.0, 0.0, 0.0);
        const double bend = 2.0 * mB.patchConcavity * gradientLength;
        PatchDepth bound = depth;
        bound.c11 -= bend;
        bound.c22 -= bend;
        if (patchPeakBound(bound, radius) <= 0.0) return;
        const auto [h11, h12, h22] =
            sampler().tangentialHessian(inB, frame.tangent1, frame.tangent2, h);
        depth = patchDepth(frame, s.phi, s.gradient, h11, h12, h22);
        NodeContact c;
        Vec3 offset;
        if (!fillPatchContact(integratePatch(depth, shape.extents, shape.reach), frame, c, offset)) return;
        ++mStats.nodesInContact;
        c.node = i;
        c.normal = mBToWorld * (s.gradient * (1.0 / gradientLength));
        c.point = mPoseB.position + mBToWorld * (inB + offset) + 0.5 * c.depth * c.normal;
        mOut.push_back(c);
    }

    /// Walk every cluster and block with the margin, and remember the nodes let through. Each
    /// node of a block let through is kept only if it too is within the margin of B's sphere
    /// and box: most nodes of a block near B are not, and every step would cull them again.
    /// Kept nodes that follow each other join into one run.
    void rememberRuns(CandidateBlocks& c)
    {
        c.valid = true;
        c.rotation = mToB;
        c.translation = mTranslation;
        c.margin = CandidateBlocks::kMarginFraction * mA.boundingRadius;
        c.runs.clear();
        const double m = c.margin;
        const Vec3* positions = mA.nodes.positions.data();
        std::vector<std::pair<int, int>>& runs = c.runs;
        NodeCheckStats ignored;
        forEachBlockNotClear(
            mA, [&](const NodeBlock& run) { return isClearWithin(run.center, run.radius, m); },
            [&](int begin, int end) {
                for (int i = begin; i < end; ++i) {
                    if (isClearWithin(positions[i], 0.0, m)) continue;
                    if (!runs.empty() && runs.back().second == i)
                        ++runs.back().second;
                    else
                        runs.emplace_back(i, i + 1);
                }
            },
            ignored);
    }

    /// The remembered nodes, each tested as a full walk would, and their sampled cells kept.
    void visitRemembered(CandidateBlocks& c, bool runsHold)
    {
        // A node just outside B's sphere may be far from B's surface, but the sphere alone
        // would say it is a hair from contact: within this of the sphere, the gap takes φ_B
        // there too (sampled for the gap only; such a node is still culled).
        mSphereBand = c.wasClear ? c.margin : 0.0;
        // Nodes sampled clear at an earlier step are passed over only while the runs hold: the
        // runs' map is what their clearUntil is measured from.
        mPassOver = runsHold;
        thread_local std::vector<CandidateBlocks::SampledCell> nextCells;
        nextCells.clear();
        mNextCells = &nextCells;
        mLastCells = &c.cells;
        if (!runsHold) {
            // Found afresh at this very map: a node sampled at φ_B above this cannot come into
            // contact while the runs hold (it moves less than the margin relative to B, and
            // φ_B changes by at most levelSetSlope per unit of distance), so it leaves them.
            // The slack covers round-off (φ_B and the move are computed, not exact).
            thread_local std::vector<int> leftOut;
            leftOut.clear();
            mLeftOut = &leftOut;
            mLeaveOutAbove = mB.levelSetSlope * c.margin * (1.0 + 1e-6) + 1e-9 * mB.levelSet->voxelSize;
        }
        long long visited = 0;
        for (const auto& [begin, end] : c.runs) {
            visited += end - begin;
            visit(begin, end);
        }
        if (mLeftOut && !mLeftOut->empty()) {
            leaveOutNodes(c.runs, *mLeftOut);
            leaveOutNodes(nextCells, *mLeftOut);
        }
        // Copied, not swapped: a swap would hand this pair the thread's buffer, grown by the
        // largest pair it served, and thousands of pairs would each end up that large.
        c.cells.assign(nextCells.begin(), nextCells.end());
        mStats.nodesCulled += static_cast<long long>(mA.nodes.size()) - visited;
    }

    /// No node in contact: each visited node is at least this far from coming into contact
    /// (outside B's sphere, outside the box, or φ_B ≥ 0 with φ_B changing by at most
    /// levelSetSlope per unit of distance), and the nodes outside the runs stay clear while
    /// the runs hold. Until a node may have moved that far, this direction can be skipped.
    void keepClearGap(CandidateBlocks& c) const
    {
        c.clearGap = 0.0;
        c.wasClear = !mAnyInside;
        if (mAnyInside) return;
        const double gap = std::min({std::sqrt(mNearestOutsideSphere2) - mReachB, mNearestInBand,
                                     mNearestOutsideBox, mSmallestPhi / mB.levelSetSlope});
        if (gap > 0.0) {
            c.clearGap = gap;
            c.clearRotation = mToB;
            c.clearTranslation = mTranslation;
        }
    }

    static constexpr double kInfinity = std::numeric_limits<double>::infinity();

    const GrainAsset& mA;
    const GrainAsset& mB;
    const RigidPose& mPoseA;
    const RigidPose& mPoseB;
    std::vector<NodeContact>& mOut;
    NodeCheckStats& mStats;
    const bool mPatches;   ///< integrate over each node's patch (PatchQuadrature.h)
    const double mReach;   ///< how far from B a node may touch it: 0, or its patch's reach
    const double mReachB;  ///< B's bounding radius and that
    const double mPerSlope;  ///< for clearUntilOf (perSlope)
    Quat mToB = Quat::Identity();
    Vec3 mTranslation = Vec3::Zero();
    Eigen::Matrix3d mRotation, mBToWorld;
    Vec3 mCenterOfB = Vec3::Zero();
    std::optional<LevelSetSampler> mSampler;
    SampleBatch mBatch;
    // Remembered candidates: the last step's sampled cells, this step's (this thread's buffer)
    // and where the walk alongside them has got.
    const std::vector<CandidateBlocks::SampledCell>* mLastCells = nullptr;
    std::vector<CandidateBlocks::SampledCell>* mNextCells = nullptr;
    size_t mCursor = 0;
    bool mPassOver = false;  ///< pass over nodes by their clearUntil (the runs hold)
    double mMove = 0.0;      ///< how far A's nodes may have moved since the runs' map, at most
    // How near the visited nodes came to contact (keepClearGap): the smallest squared distance
    // to B's centre of those outside its sphere, the smallest distance outside the inside box
    // along an axis, the smallest φ_B ≥ 0 sampled, the gaps of nodes in the band just outside
    // the sphere; and whether any φ_B < 0.
    double mNearestOutsideSphere2 = kInfinity;
    double mNearestOutsideBox = kInfinity;
    double mSmallestPhi = kInfinity;
    double mNearestInBand = kInfinity;
    bool mAnyInside = false;
    double mSphereBand = 0.0;           ///< 0: no band's gap is kept
    double mLeaveOutAbove = kInfinity;  ///< infinite: no node leaves the runs
    std::vector<int>* mLeftOut = nullptr;  ///< such nodes, ascending (this thread's buffer)
};

} // namespace

void findNodeContacts(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out,
                      NodeCheckStats& stats, CandidateBlocks* candidates, bool patches)
{
    NodeContactSearch(a, poseA, b, poseB, out, stats, patches).run(candidates);
}

} // namespace lsdem
