/// @file NodeBlockWalk.h
/// @brief Visit the nodes of a grain that a contact test cannot rule out: cluster by cluster
///        and block by block (NodeBlocks), skipping every cluster or block whose bounding
///        sphere the test finds clear of the other body. Shared by the grain, plane and sphere
///        narrow phases, each with its own test.
#pragma once

#include "lsdem/contact/NodeContact.h"

#include <stdexcept>

namespace lsdem {

/// Call @a visit(begin, end) for every run of nodes [begin, end) of @a a that lies in a
/// cluster for which @a isClusterClear(cluster) is false and a block for which
/// @a isBlockClear(block) is false, in node order; the others count as culled in @a stats.
/// Each test must only answer true when no node within the run's sphere can touch. A block is
/// asked only after its cluster, and just before it is visited (so a test may keep what it
/// learnt of a cluster for its blocks); a grain without blocks is visited whole, unasked. The
/// visitor takes a whole block, so its loop over the nodes is compiled inline.
template <typename IsClusterClear, typename IsBlockClear, typename Visit>
void forEachBlockNotClear(const GrainAsset& a, IsClusterClear&& isClusterClear,
                          IsBlockClear&& isBlockClear, Visit&& visit, NodeCheckStats& stats)
{
    const int count = static_cast<int>(a.nodes.size());
    const NodeBlocks& groups = a.nodeBlocks;
    if (groups.empty()) {
        visit(0, count);
        return;
    }
    // Blocks left over from other nodes would silently drop contacts: refuse them.
    if (!groups.matches(a.nodes.size()))
        throw std::logic_error("grain asset: node blocks do not match the nodes; call "
                               "groupNodesIntoBlocks after changing them");
    for (const NodeBlock& cluster : groups.clusters) {
        if (isClusterClear(cluster)) {
            stats.nodesCulled += groups.blocks[static_cast<size_t>(cluster.end - 1)].end -
                                 groups.blocks[static_cast<size_t>(cluster.begin)].begin;
            continue;
        }
        for (int k = cluster.begin; k < cluster.end; ++k) {
            const NodeBlock& block = groups.blocks[static_cast<size_t>(k)];
            if (isBlockClear(block)) {
                stats.nodesCulled += block.end - block.begin;
                continue;
            }
            visit(block.begin, block.end);
        }
    }
}

/// The same with one test, @a isClear(run), for clusters and blocks alike.
template <typename IsClear, typename Visit>
void forEachBlockNotClear(const GrainAsset& a, IsClear&& isClear, Visit&& visit,
                          NodeCheckStats& stats)
{
    forEachBlockNotClear(a, isClear, isClear, visit, stats);
}

} // namespace lsdem
