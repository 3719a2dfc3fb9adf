/// @file MeshEdgeUses.h
/// @brief Each triangle's use of each undirected edge, sorted so the uses of one edge are
///        adjacent (private to lsdem_mesh): the validation finds open and non-manifold edges
///        with them, the node layout sharp ones.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace lsdem {

/// One triangle's use of an undirected edge.
struct EdgeUse
{
    std::uint64_t key;  ///< (lower vertex << 32) | higher vertex
    int triangle;
    bool forward;  ///< the triangle runs along the edge from the lower to the higher vertex
};

/// Every edge use of every triangle, sorted so the uses of one edge are adjacent.
inline std::vector<EdgeUse> collectEdgeUses(const TriangleMesh& mesh)
{
    std::vector<EdgeUse> uses;
    uses.reserve(3 * mesh.triangles.size());
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::uint32_t>(mesh.triangles[t][k]);
            const auto b = static_cast<std::uint32_t>(mesh.triangles[t][(k + 1) % 3]);
            const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            uses.push_back({key, t, a < b});
        }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
    });
    return uses;
}

} // namespace lsdem
