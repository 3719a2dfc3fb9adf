/// @file CandidateBlocks.h
/// @brief The nodes of grain A that may touch grain B, remembered over several steps.
///
/// Finding which of A's nodes are near B walks every cluster and block of A; two grains that
/// stay in contact for thousands of steps find the same few nodes every time. The list is
/// found with every bounding sphere grown by a margin m (blocks, then their nodes, each
/// within m of B's sphere and of the box of B's inside), together with the rigid map from A's
/// frame to B's at that moment. While no node of A has since moved more than m relative to B,
/// every node clear of B now was clear of B with the margin then, so visiting only the listed
/// nodes (each still tested as a full walk tests it) finds exactly the contacts a full walk
/// finds, in the same order. A node sampled at φ_B > L·m when the list is made (L the slope
/// bound of B's level set) leaves it too: within m of where it was, φ_B stays positive.
/// A node x of A moves relative to B by at most
/// |Δt| + 2 sin(θ/2)·|x|, where Δt and θ are the change of the map's translation and the angle
/// of its change of rotation, and |x| is at most A's bounding radius.
///
/// It also keeps, for each listed node sampled in B at the last step (or passed over, below),
/// the voxel cell it was last sampled in and that cell's corner values: contacts last thousands
/// of steps and a node moves a tiny fraction of a voxel per step, so most samples are
/// interpolated from these (read in order, one stream) instead of from the grid's leaves
/// (scattered), with the same result.
///
/// And a node sampled clear of B is passed over at the next steps, not sampled, while A cannot
/// have moved far enough since to bring it into contact (SampledCell::clearUntil): the nodes
/// just outside a contact patch are about half of those sampled in a pressed slab, and most of
/// them stay clear for many steps. The contacts are the same.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/ls/LevelSetCell.h"

#include <utility>
#include <vector>

namespace lsdem {

struct CandidateBlocks
{
    /// The margin as a fraction of A's bounding radius: larger visits more nodes each step,
    /// smaller refreshes the list more often.
    static constexpr double kMarginFraction = 0.02;

    bool valid = false;
    Quat rotation = Quat::Identity();     ///< A's frame to B's when the list was made
    Vec3 translation = Vec3::Zero();
    double margin = 0.0;                  ///< length
    std::vector<std::pair<int, int>> runs;  ///< A's nodes [begin, end) kept, ascending

    /// When A last found no contact with B: the map from A's frame to B's then, and a gap
    /// below which no node of the runs could have moved into contact (see clearOfContact).
    /// 0: not known clear.
    Quat clearRotation = Quat::Identity();
    Vec3 clearTranslation = Vec3::Zero();
    double clearGap = 0.0;  ///< length
    /// Whether the last walk found A clear of B: only then does the next one also sample φ_B
    /// at the nodes just outside B's sphere, for a gap worth keeping (a pair in contact
    /// would pay for it at every step and never use it).
    bool wasClear = false;

    /// A node of A sampled in B at the last step, or passed over then, and the cell of B it was
    /// last sampled in.
    struct SampledCell
    {
        int node = 0;
        /// While A has moved less than this (largestMove from the runs' map, length) the node
        /// cannot have reached B, and is passed over instead of sampled. A node sampled at φ_B
        /// = φ when A had moved m_s has moved at most m + m_s since, where m is A's move now,
        /// and φ_B changes by at most levelSetSlope a unit of distance, so this is (φ − reach)/
        /// slope − m_s, rounded down (with a slack for round-off, as the runs' margin has).
        /// Negative for a node in contact; made anew when the runs are.
        float clearUntil = -1.0f;
        LevelSetCell cell;
    };
    std::vector<SampledCell> cells;  ///< ascending by node

    /// Whether the list still holds every block that can touch B under the map (@a rotation,
    /// @a translation) for a grain A whose nodes lie within @a reachA of its origin.
    bool holds(const Quat& rotationNow, const Vec3& translationNow, double reachA) const
    {
        return holdsAfter(moveSinceRuns(rotationNow, translationNow, reachA));
    }

    /// The same for a move of A's nodes since the runs' map of @a move at most.
    bool holdsAfter(double move) const { return valid && move < margin; }

    /// How far a node of A within @a reachA of its origin has moved relative to B since the
    /// runs' map, at most (largestMove).
    double moveSinceRuns(const Quat& rotationNow, const Vec3& translationNow, double reachA) const
    {
        return largestMove(rotation, translation, rotationNow, translationNow, reachA);
    }

    /// Whether A's runs are still sure to be clear of B: A found none of their nodes in contact
    /// under the map (clearRotation, clearTranslation), each at least clearGap from it, and no
    /// node has moved half that far since. Half: a margin for round-off far larger than it.
    bool clearOfContact(const Quat& rotationNow, const Vec3& translationNow, double reachA) const
    {
        return clearGap > 0.0 && largestMove(clearRotation, clearTranslation, rotationNow,
                                             translationNow, reachA) < 0.5 * clearGap;
    }

    /// How far a node of A within @a reachA of its origin has moved relative to B from the map
    /// (q0, t0) to (q1, t1), at most: |Δt| + 2 sin(θ/2)·reachA.
    static double largestMove(const Quat& q0, const Vec3& t0, const Quat& q1, const Vec3& t1,
                              double reachA)
    {
        // |vec(q)| = sin(θ/2) for the unit quaternion of the change of rotation.
        const Quat change = q1 * q0.conjugate();
        return (t1 - t0).norm() + 2.0 * change.vec().norm() * reachA;
    }
};

/// Remove the nodes @a nodes (ascending, each in one of the runs) from the runs [begin, end)
/// of @a runs (ascending), splitting a run where a node leaves its middle.
void leaveOutNodes(std::vector<std::pair<int, int>>& runs, const std::vector<int>& nodes);

/// Remove from @a cells (ascending by node) those of the nodes @a nodes (ascending).
void leaveOutNodes(std::vector<CandidateBlocks::SampledCell>& cells, const std::vector<int>& nodes);

/// Both directions of a grain pair: the first grain's nodes near the second, and back.
struct PairCandidates
{
    CandidateBlocks ofFirst, ofSecond;
};

} // namespace lsdem
