/// @file VertexTriangles.h
/// @brief The triangles around each vertex of a mesh (private to lsdem_mesh): the validation
///        finds each triangle's neighbours with it, the pseudo-normals the triangle across
///        each edge, the node layout the sharp edges. Four bytes per triangle corner and one
///        word per vertex, a third of a sorted list of every edge's uses.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace lsdem {

class VertexTriangles
{
public:
    /// The mesh's vertex indices must be in range; @a mesh must outlive this, unchanged.
    explicit VertexTriangles(const TriangleMesh& mesh) : mMesh(mesh)
    {
        // Counts, running sums, then the triangles, each vertex's in increasing order.
        const size_t vertices = mesh.vertices.size();
        mFirst.assign(vertices + 1, 0);
        for (const auto& tri : mesh.triangles)
            for (int v : tri) ++mFirst[size_t(v) + 1];
        for (size_t v = 1; v <= vertices; ++v) mFirst[v] += mFirst[v - 1];
        mAround.resize(mFirst.back());
        std::vector<uint32_t> next(mFirst.begin(), mFirst.end() - 1);
        for (size_t t = 0; t < mesh.triangles.size(); ++t)
            for (int v : mesh.triangles[t]) mAround[next[size_t(v)]++] = int32_t(t);
    }

    /// Calls @a visit(t) for each triangle t with a corner at vertex @a v, in increasing order
    /// (a triangle with v at two corners, twice).
    template <typename Visit>
    void forEachAround(int v, Visit&& visit) const
    {
        for (uint32_t i = mFirst[size_t(v)]; i < mFirst[size_t(v) + 1]; ++i) visit(int(mAround[i]));
    }

    /// Calls @a visit(t) for each triangle t with an edge between vertices @a a and @a b
    /// (either way round; a ≠ b), in increasing order (a triangle with two corners at a,
    /// twice: it has that edge twice).
    template <typename Visit>
    void forEachUsingEdge(int a, int b, Visit&& visit) const
    {
        forEachAround(a, [&](int t) {
            const auto& tri = mMesh.triangles[size_t(t)];
            if (tri[0] == b || tri[1] == b || tri[2] == b) visit(t);  // any two corners: an edge
        });
    }

private:
    const TriangleMesh& mMesh;
    std::vector<uint32_t> mFirst;  ///< per vertex, where its triangles begin in mAround
    std::vector<int32_t> mAround;
};

} // namespace lsdem
