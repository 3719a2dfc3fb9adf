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
/// cluster and a block for which @a isClear(run) is false, in node order; the others count as
/// culled in @a stats. @a isClear(const NodeBlock&) must only answer true when no node within
/// the run's sphere can touch (it is asked of clusters and of blocks alike). The visitor takes
/// a whole block, so its loop over the nodes is compiled inline.
template <typename IsClear, typename Visit>
void forEachBlockNotClear(const GrainAsset& a, IsClear&& isClear, Visit&& visit,
                          NodeCheckStats& stats)
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
        if (isClear(cluster)) {
            stats.nodesCulled += groups.blocks[static_cast<size_t>(cluster.end - 1)].end -
                                 groups.blocks[static_cast<size_t>(cluster.begin)].begin;
            continue;
        }
        for (int k = cluster.begin; k < cluster.end; ++k) {
            const NodeBlock& block = groups.blocks[static_cast<size_t>(k)];
            if (isClear(block)) {
                stats.nodesCulled += block.end - block.begin;
                continue;
            }
            visit(block.begin, block.end);
        }
    }
}

} // namespace lsdem
