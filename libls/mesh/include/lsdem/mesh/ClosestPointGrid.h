/// @file ClosestPointGrid.h
/// @brief The closest point of a triangle mesh to a query point, through a uniform grid of
///        cells that lists the triangles whose bounding box meets each cell.
///
/// Made for points near the surface (a remesher putting its vertices back onto its input):
/// the query reads the point's own cell, then only the cells within the distance found so
/// far; a point far from the surface reads many cells. A few megabytes for a 100k-triangle
/// mesh, where a bounding-volume tree with its distance accelerator holds tens. Triangles may
/// carry labels (the patches between a surface's sharp edges) and a query may keep to one.
#pragma once

#include "lsdem/core/Vec3.h"
#include "lsdem/mesh/TriangleMesh.h"

#include <array>
#include <vector>

namespace lsdem {

class ClosestPointGrid
{
public:
    /// @a vertices and @a triangles are copied; @a labels, if not empty, has one per triangle.
    /// Cells are about @a cellSize wide, wider when the box of the mesh would need more than a
    /// few cells per triangle. Triangles of zero area are left out: on a closed surface their
    /// edges belong to neighbours with area, which hold every point they would add.
    ClosestPointGrid(std::vector<Vec3> vertices, std::vector<std::array<int, 3>> triangles,
                     double cellSize, std::vector<int> labels = {});

    /// A grid over @a mesh without a copy of it (a node placer's peak holds one mesh less):
    /// @a mesh must outlive the grid, unchanged. No labels.
    ClosestPointGrid(const TriangleMesh& mesh, double cellSize);
    ClosestPointGrid(TriangleMesh&& mesh, double cellSize) = delete;  // it would not outlive it

    // Moved, the vectors keep their storage, which mVertexData and mTriangleData point into.
    ClosestPointGrid(ClosestPointGrid&&) = default;
    ClosestPointGrid(const ClosestPointGrid&) = delete;
    ClosestPointGrid& operator=(const ClosestPointGrid&) = delete;
    ClosestPointGrid& operator=(ClosestPointGrid&&) = delete;

    /// The point closest to @a p of the triangles labelled @a label (of every triangle if
    /// @a label is negative); of several at the same distance, the first triangle's. Exact up
    /// to round-off. @a p itself if no triangle has the label.
    Vec3 closestPoint(const Vec3& p, int label = -1) const;

    double cellSize() const { return mCell; }

private:
    /// Checks the mesh and lists each triangle of area in the cells its box meets.
    void build(double cellSize);
    std::array<int, 3> cellOf(const Vec3& p) const;  // clamped into the grid
    size_t indexOf(int i, int j, int k) const
    {
        return (size_t(k) * size_t(mDims[1]) + size_t(j)) * size_t(mDims[0]) + size_t(i);
    }
    /// Tests the triangles of cell (i, j, k) against @a p, keeping the nearest in @a best.
    void testCell(int i, int j, int k, const Vec3& p, int label, double& best2,
                  Vec3& bestOffset, int& bestTriangle) const;

    std::vector<Vec3> mOwnedVertices;  ///< empty over a caller's mesh
    std::vector<std::array<int, 3>> mOwnedTriangles;
    const Vec3* mVertexData = nullptr;  ///< the owned vertices or the caller's
    const std::array<int, 3>* mTriangleData = nullptr;
    size_t mVertexCount = 0, mTriangleCount = 0;
    std::vector<int> mLabels;  ///< per triangle; empty: no labels (all 0)
    Vec3 mOrigin = Vec3::Zero();
    double mCell = 1.0;
    std::array<int, 3> mDims{1, 1, 1};
    std::vector<int> mCellStart;   ///< per cell, where its triangles begin in mCellTriangles
    std::vector<int> mCellTriangles;
};

} // namespace lsdem
