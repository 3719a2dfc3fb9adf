#include "lsdem/mesh/ClosestPointGrid.h"

#include "lsdem/core/Error.h"
#include "lsdem/mesh/TriangleOffset.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace lsdem {

ClosestPointGrid::ClosestPointGrid(std::vector<Vec3> vertices,
                                   std::vector<std::array<int, 3>> triangles, double cellSize,
                                   std::vector<int> labels)
    : mOwnedVertices(std::move(vertices)), mOwnedTriangles(std::move(triangles)),
      mVertexData(mOwnedVertices.data()), mTriangleData(mOwnedTriangles.data()),
      mVertexCount(mOwnedVertices.size()), mTriangleCount(mOwnedTriangles.size()),
      mLabels(std::move(labels))
{
    if (!mLabels.empty() && mLabels.size() != mTriangleCount)
        throw Error("", "closest-point grid: " + std::to_string(mLabels.size()) + " labels for " +
                            std::to_string(mTriangleCount) + " triangles");
    build(cellSize);
}

ClosestPointGrid::ClosestPointGrid(const TriangleMesh& mesh, double cellSize)
    : mVertexData(mesh.vertices.data()), mTriangleData(mesh.triangles.data()),
      mVertexCount(mesh.vertices.size()), mTriangleCount(mesh.triangles.size())
{
    build(cellSize);
}

void ClosestPointGrid::build(double cellSize)
{
    if (!(std::isfinite(cellSize) && cellSize > 0.0))
        throw Error("", "closest-point grid: the cell size must be positive");
    for (size_t v = 0; v < mVertexCount; ++v)
        if (!mVertexData[v].allFinite())
            throw Error("", "closest-point grid: a vertex is not finite");
    if (mVertexCount > size_t(std::numeric_limits<int>::max()))
        throw Error("", "closest-point grid: too many vertices");
    if (mTriangleCount > size_t(std::numeric_limits<int>::max()))
        throw Error("", "closest-point grid: too many triangles");
    const int vertexCount = static_cast<int>(mVertexCount);
    auto hasArea = [&](const std::array<int, 3>& t) {
        const Vec3 &a = mVertexData[t[0]], &b = mVertexData[t[1]], &c = mVertexData[t[2]];
        return (b - a).cross(c - a).squaredNorm() != 0.0;
    };
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    size_t withArea = 0;
    for (size_t n = 0; n < mTriangleCount; ++n) {
        const std::array<int, 3>& t = mTriangleData[n];
        for (int v : t)
            if (v < 0 || v >= vertexCount)
                throw Error("", "closest-point grid: a triangle refers to vertex " +
                                    std::to_string(v) + " of " + std::to_string(vertexCount));
        if (!hasArea(t)) continue;
        ++withArea;
        for (int v : t) {
            lo = lo.cwiseMin(mVertexData[v]);
            hi = hi.cwiseMax(mVertexData[v]);
        }
    }
    if (withArea == 0) throw Error("", "closest-point grid: the mesh has no triangles");
    // At most about 4 cells per triangle (plus a few): a coarse mesh in a big box would
    // otherwise ask for more cells than it has triangles by far.
    const Vec3 extent = (hi - lo).cwiseMax(1e-12 * std::max(1.0, (hi - lo).maxCoeff()));
    const double cellBudget = 4.0 * double(withArea) + 64.0;
    mCell = std::max(cellSize, std::cbrt(extent.prod() / cellBudget));
    auto countCells = [&] {
        for (int k = 0; k < 3; ++k)
            mDims[size_t(k)] = std::max(1, int(std::ceil(extent[k] / mCell)));
        return double(mDims[0]) * double(mDims[1]) * double(mDims[2]);
    };
    for (int k = 0; k < 3; ++k) mCell = std::max(mCell, extent[k] / 1e6);  // counts fit an int
    while (countCells() > 8.0 * cellBudget) mCell *= 2.0;  // flat or thin boxes
    mOrigin = lo;

    // Each triangle of area is listed in every cell its bounding box meets: the cells'
    // boxes, then their counts, then the triangles placed (each cell's in increasing order).
    auto cellBox = [&](const std::array<int, 3>& t) {
        const Vec3 &a = mVertexData[t[0]], &b = mVertexData[t[1]], &c = mVertexData[t[2]];
        return std::make_pair(cellOf(a.cwiseMin(b).cwiseMin(c)), cellOf(a.cwiseMax(b).cwiseMax(c)));
    };
    auto forEachCell = [&](const std::array<int, 3>& t, auto&& f) {
        const auto [from, to] = cellBox(t);
        for (int k = from[2]; k <= to[2]; ++k)
            for (int j = from[1]; j <= to[1]; ++j)
                for (int i = from[0]; i <= to[0]; ++i) f(indexOf(i, j, k));
    };
    // Long thin triangles across a big grid could list more entries than an int counts.
    size_t entries = 0;
    for (size_t n = 0; n < mTriangleCount; ++n) {
        if (!hasArea(mTriangleData[n])) continue;
        const auto [from, to] = cellBox(mTriangleData[n]);
        entries += size_t(to[0] - from[0] + 1) * size_t(to[1] - from[1] + 1) *
                   size_t(to[2] - from[2] + 1);
    }
    if (entries > size_t(std::numeric_limits<int>::max()))
        throw Error("", "closest-point grid: the triangles meet too many cells",
                    "use a larger cell size");
    const size_t cells = size_t(mDims[0]) * size_t(mDims[1]) * size_t(mDims[2]);
    // Counted into the slot after each cell's, summed into each cell's start; placing a
    // triangle moves its cell's start on, so each start ends at the next cell's and the whole
    // is shifted back by one (no second array of cursors).
    mCellStart.assign(cells + 1, 0);
    for (size_t n = 0; n < mTriangleCount; ++n)
        if (hasArea(mTriangleData[n]))
            forEachCell(mTriangleData[n], [&](size_t cell) { ++mCellStart[cell + 1]; });
    for (size_t cell = 0; cell < cells; ++cell) mCellStart[cell + 1] += mCellStart[cell];
    mCellTriangles.resize(entries);
    for (size_t n = 0; n < mTriangleCount; ++n)
        if (hasArea(mTriangleData[n]))
            forEachCell(mTriangleData[n],
                        [&](size_t cell) { mCellTriangles[size_t(mCellStart[cell]++)] = int(n); });
    for (size_t cell = cells; cell > 0; --cell) mCellStart[cell] = mCellStart[cell - 1];
    mCellStart[0] = 0;
}

std::array<int, 3> ClosestPointGrid::cellOf(const Vec3& p) const
{
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k) {
        const double x = std::floor((p[k] - mOrigin[k]) / mCell);
        c[size_t(k)] = int(std::clamp(x, 0.0, double(mDims[size_t(k)] - 1)));
    }
    return c;
}

void ClosestPointGrid::testCell(int i, int j, int k, const Vec3& p, int label, double& best2,
                                Vec3& bestOffset, int& bestTriangle) const
{
    const size_t cell = indexOf(i, j, k);
    for (int e = mCellStart[cell]; e < mCellStart[cell + 1]; ++e) {
        const int n = mCellTriangles[size_t(e)];
        if (label >= 0 && (mLabels.empty() ? 0 : mLabels[size_t(n)]) != label) continue;
        const auto& t = mTriangleData[n];
        const Vec3 offset =
            offsetFromTriangle(p, mVertexData[t[0]], mVertexData[t[1]], mVertexData[t[2]]);
        const double d2 = offset.squaredNorm();
        if (d2 < best2 || (d2 == best2 && n < bestTriangle)) {
            best2 = d2;
            bestOffset = offset;
            bestTriangle = n;
        }
    }
}

Vec3 ClosestPointGrid::closestPoint(const Vec3& p, int label) const
{
    double best2 = std::numeric_limits<double>::infinity();
    Vec3 bestOffset = Vec3::Zero();
    int bestTriangle = std::numeric_limits<int>::max();
    const std::array<int, 3> home = cellOf(p);
    // Rings of cells around the point's own until one holds a triangle (with the label): a
    // point near the surface stops at the first.
    int ring = 0;
    const int maxRing = std::max({mDims[0], mDims[1], mDims[2]});
    for (; ring <= maxRing && !(best2 < std::numeric_limits<double>::infinity()); ++ring)
        for (int k = home[2] - ring; k <= home[2] + ring; ++k)
            for (int j = home[1] - ring; j <= home[1] + ring; ++j)
                for (int i = home[0] - ring; i <= home[0] + ring; ++i) {
                    const bool onShell = std::max({std::abs(i - home[0]), std::abs(j - home[1]),
                                                   std::abs(k - home[2])}) == ring;
                    if (!onShell || i < 0 || j < 0 || k < 0 || i >= mDims[0] ||
                        j >= mDims[1] || k >= mDims[2])
                        continue;
                    testCell(i, j, k, p, label, best2, bestOffset, bestTriangle);
                }
    if (!(best2 < std::numeric_limits<double>::infinity())) return p;  // no such triangle
    // Any nearer triangle meets the ball of the distance found, so it is listed in a cell that
    // the ball's box meets: the cells of that box not read yet are read (the ball only
    // shrinks as they are). A hair of slack covers the round-off of the cell arithmetic.
    const double reach = std::sqrt(best2) * (1.0 + 1e-9) + 1e-12 * mCell;
    const std::array<int, 3> from = cellOf(p - Vec3::Constant(reach)),
                             to = cellOf(p + Vec3::Constant(reach));
    const int done = ring - 1;  // rings 0..done around home were read
    for (int k = from[2]; k <= to[2]; ++k)
        for (int j = from[1]; j <= to[1]; ++j)
            for (int i = from[0]; i <= to[0]; ++i) {
                if (std::max({std::abs(i - home[0]), std::abs(j - home[1]),
                              std::abs(k - home[2])}) <= done)
                    continue;
                testCell(i, j, k, p, label, best2, bestOffset, bestTriangle);
            }
    return p - bestOffset;
}

} // namespace lsdem
