/// @file NodeContact.h
/// @brief The narrow phase: the nodes of one grain that penetrate another grain's level set,
///        with their depth, normal and contact point. Shared by every contact formulation.
#pragma once

#include "lsdem/contact/RigidPose.h"
#include "lsdem/ls/GrainAsset.h"

#include <vector>

namespace lsdem {

struct CandidateBlocks;

/// One penetrating node of grain A inside grain B (world frame).
struct NodeContact
{
    int node = 0;                  ///< index into A's nodes
    /// Patch quadrature only (below): the deepest point of the patch, length. A float, so it
    /// fits beside @a node where the double after it would leave a gap (the narrow phase
    /// writes and reads these by the hundred thousand).
    float peakDepth = 0.0f;
    double depth = 0.0;            ///< d = -φ_B(node) > 0, length
    Vec3 normal = Vec3::Zero();    ///< unit ∇φ_B at the node: pushes A out of B
    Vec3 point = Vec3::Zero();     ///< contact point: the node moved d/2 toward B's surface
    double area = 0.0;             ///< the node's tributary area, length²
    /// Patch quadrature (PatchQuadrature.h) only; 0 for a node taken as a point. With it,
    /// @a area is the part of the node's patch in contact, @a depth the mean depth over that
    /// part (so k·area·depth is the traction's integral) and @a point its centre.
    double squareDepth = 0.0;      ///< mean of d² over the part in contact, length²

    /// The mean of d² over the contact (the elastic energy is ½·k·area·this).
    double meanSquareDepth() const { return squareDepth > 0.0 ? squareDepth : depth * depth; }
    /// The deepest point of the contact: the node, or the deepest point of its patch.
    double deepest() const { return peakDepth > 0.0f ? double(peakDepth) : depth; }
    bool isPatch() const { return peakDepth > 0.0f; }
};

/// Counters of the narrow phase, to report node checks per second and culling efficiency.
struct NodeCheckStats
{
    long long nodesConsidered = 0;  ///< nodes of A looked at
    long long nodesCulled = 0;      ///< rejected by bounds before sampling φ_B
    long long nodesSampled = 0;     ///< φ_B evaluated
    long long nodesInContact = 0;   ///< φ_B < 0
    /// Of the culled: remembered nodes passed over because they were sampled clear of B at an
    /// earlier step and have not moved far enough since to reach it (CandidateBlocks.h).
    long long nodesPassedOver = 0;

    NodeCheckStats& operator+=(const NodeCheckStats& o)
    {
        nodesConsidered += o.nodesConsidered;
        nodesCulled += o.nodesCulled;
        nodesSampled += o.nodesSampled;
        nodesInContact += o.nodesInContact;
        nodesPassedOver += o.nodesPassedOver;
        return *this;
    }
};

/// Append to @a out every node of grain A (asset @a a at @a poseA) with φ_B < 0, in node order.
/// Nodes outside B's bounding sphere are culled without sampling.
/// @param candidates  if not null, the blocks of A near B found at an earlier call for the
///                    same pair, used while they hold and refreshed when they do not: the
///                    contacts are the same as without it (see CandidateBlocks.h)
/// @param patches     integrate over each node's patch (PatchQuadrature.h): every node whose
///                    patch reaches into B; A must carry its node shapes
void findNodeContacts(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out,
                      NodeCheckStats& stats, CandidateBlocks* candidates = nullptr,
                      bool patches = false);

} // namespace lsdem
