#include "lsdem/contact/NodeContact.h"

#include "lsdem/ls/LevelSetSampler.h"

#include <optional>
#include <stdexcept>

namespace lsdem {

void findNodeContacts(const GrainAsset& a, const RigidPose& poseA, const GrainAsset& b,
                      const RigidPose& poseB, std::vector<NodeContact>& out,
                      NodeCheckStats& stats)
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
    const Eigen::Matrix3d rotation = toB.toRotationMatrix();
    const Vec3 translation = poseB.orientation.conjugate() * (poseA.position - poseB.position);
    const Eigen::Matrix3d bToWorld = poseB.orientation.toRotationMatrix();
    const double reach2 = reachB * reachB;

    // The accessor costs ~100 ns to make: only when some node gets near B.
    std::optional<LevelSetSampler> sampler;
    auto testNodes = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 inB = rotation * a.nodes.positions[i] + translation;
            if (inB.squaredNorm() > reach2) {  // outside B's bounding sphere: φ_B > 0
                ++stats.nodesCulled;
                continue;
            }
            ++stats.nodesSampled;
            if (!sampler) sampler.emplace(*b.levelSet);
            const LevelSetSample s = sampler->sample(inB);
            if (!(s.phi < 0.0)) continue;
            const double gradientLength = s.gradient.norm();
            if (gradientLength == 0.0) continue;  // no direction to push (degenerate level set)
            ++stats.nodesInContact;
            NodeContact c;
            c.node = i;
            c.depth = -s.phi;
            c.normal = bToWorld * (s.gradient / gradientLength);
            const Vec3 nodeWorld = poseB.position + bToWorld * inB;
            c.point = nodeWorld + 0.5 * c.depth * c.normal;
            c.area = a.nodes.areas[i];
            out.push_back(c);
        }
    };
    if (a.nodeBlocks.empty()) {
        testNodes(0, static_cast<int>(count));
        return;
    }
    // Blocks left over from other nodes would silently drop contacts: refuse them.
    if (a.nodeBlocks.back().end != static_cast<int>(count))
        throw std::logic_error("grain asset: node blocks do not match the nodes; call "
                               "groupNodesIntoBlocks after changing them");
    // Whole blocks of nearby nodes whose bounding sphere misses B's are skipped unsampled.
    for (const NodeBlock& block : a.nodeBlocks) {
        const Vec3 centerInB = rotation * block.center + translation;
        const double reach = reachB + block.radius;
        if (centerInB.squaredNorm() > reach * reach) {
            stats.nodesCulled += block.end - block.begin;
            continue;
        }
        testNodes(block.begin, block.end);
    }
}

} // namespace lsdem
