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
    double depth = 0.0;            ///< d = -φ_B(node) > 0, length
    Vec3 normal = Vec3::Zero();    ///< unit ∇φ_B at the node: pushes A out of B
    Vec3 point = Vec3::Zero();     ///< contact point: the node moved d/2 toward B's surface
    double area = 0.0;             ///< the node's tributary area, length²
};

/// Counters of the narrow phase, to report node checks per second and culling efficiency.
struct NodeCheckStats
{
    long long nodesConsidered = 0;  ///< nodes of A looked at
    long long nodesCulled = 0;      ///< rejected by bounds before sampling φ_B
    long long nodesSampled = 0;     ///< φ_B evaluated
    long long nodesInContact = 0;   ///< φ_B < 0

    NodeCheckStats& operator+=(const NodeCheckStats& o)
    {
        nodesConsidered += o.nodesConsidered;
        nodesCulled += o.nodesCulled;
        nodesSampled += o.nodesSampled;
        nodesInContact += o.nodesInContact;
        return *this;
    }
};

/// Append to @a out every node of grain A (asset @a a at @a poseA) with φ_B < 0, in node order.
/// Nodes outside B's bounding sphere are culled without sampling.
/// @param candidates  if not null, the blocks of A near B found at an earlier call for the
///                    same pair, used while they hold and refreshed when they do not: the
///                    contacts are the same as without it (see CandidateBlocks.h)
void findNodeContacts(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out,
                      NodeCheckStats& stats, CandidateBlocks* candidates = nullptr);

} // namespace lsdem
