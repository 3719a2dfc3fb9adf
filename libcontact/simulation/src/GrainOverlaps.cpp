#include "lsdem/simulation/GrainOverlaps.h"

#include "lsdem/core/ThreadPrivate.h"
#include "lsdem/simulation/BroadPhase.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace lsdem {

std::vector<GrainOverlap> findGrainOverlaps(const World& world)
{
    const size_t n = world.grains.size();
    std::vector<Vec3> centers(n);
    std::vector<double> radii(n);
    for (size_t i = 0; i < n; ++i) {
        centers[i] = world.grains[i].body.pose.position;
        radii[i] = world.grains[i].asset->boundingRadius;
    }
    const std::vector<std::pair<int, int>> pairs = findCandidatePairs(centers, radii);
    std::vector<double> depth(pairs.size(), 0.0);
    tbb::enumerable_thread_specific<ThreadPrivate<std::vector<NodeContact>>> buffers;
    tbb::parallel_for(size_t(0), pairs.size(), [&](size_t k) {
        std::vector<NodeContact>& contacts = buffers.local().value;
        const Grain& a = world.grains[size_t(pairs[k].first)];
        const Grain& b = world.grains[size_t(pairs[k].second)];
        NodeCheckStats stats;
        contacts.clear();
        findNodeContacts(*a.asset, a.body.pose, *b.asset, b.body.pose, contacts, stats);
        findNodeContacts(*b.asset, b.body.pose, *a.asset, a.body.pose, contacts, stats);
        for (const NodeContact& c : contacts) depth[k] = std::max(depth[k], c.depth);
    });
    std::vector<GrainOverlap> out;
    for (size_t k = 0; k < pairs.size(); ++k)
        if (depth[k] > 0.0) out.push_back({pairs[k].first, pairs[k].second, depth[k]});
    return out;
}

} // namespace lsdem
