#include "MeshNarrowBand.h"

#include "ClosestTriangleGrid.h"

#include "lsdem/mesh/MeshPseudoNormals.h"
#include "lsdem/mesh/TriangleOffset.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace lsdem {

namespace {

using closest::CodeLeaf;
constexpr int kLeafDim = CodeLeaf::kDim;
constexpr int kLeafLog2 = CodeLeaf::kLog2Dim;

/// The voxels within a reach of each triangle's box, as index ranges [lo, hi] per axis.
struct VoxelRange
{
    openvdb::Coord lo, hi;
};

VoxelRange reachOf(const TriangleMesh& mesh, int t, const Vec3& origin, double voxel,
                   double reachVoxels)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int k = 0; k < 3; ++k) {
        const Vec3 index = (mesh.vertices[size_t(mesh.triangles[size_t(t)][k])] - origin) / voxel;
        lo = lo.cwiseMin(index);
        hi = hi.cwiseMax(index);
    }
    VoxelRange r;
    for (int a = 0; a < 3; ++a) {
        r.lo[a] = int(std::ceil(lo[a] - reachVoxels));
        r.hi[a] = int(std::floor(hi[a] + reachVoxels));
    }
    return r;
}

/// The triangles that can be nearest to some band voxel of each 8³ leaf of the grid: those
/// whose box, widened by the band, meets the leaf, listed in increasing order a leaf.
class LeafTriangles
{
public:
    LeafTriangles(const TriangleMesh& mesh, const Vec3& origin, double voxel, double reachVoxels)
    {
        // Each triangle's range of leaves, made again in each pass rather than stored (it
        // would take 24 bytes a triangle).
        auto leavesOf = [&](int t) {
            VoxelRange r = reachOf(mesh, t, origin, voxel, reachVoxels);
            for (int a = 0; a < 3; ++a) {
                r.lo[a] >>= kLeafLog2;  // (index space lies in the positive octant)
                r.hi[a] >>= kLeafLog2;
            }
            return r;
        };
        const int triangles = int(mesh.triangles.size());
        openvdb::Coord lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
        for (int t = 0; t < triangles; ++t) {
            const VoxelRange r = leavesOf(t);
            lo.minComponent(r.lo);
            hi.maxComponent(r.hi);
        }
        mLow = lo;
        for (int a = 0; a < 3; ++a) mDim[a] = size_t(hi[a] - lo[a] + 1);
        // A counting sort into a dense table of the leaves: counts, their running sums, then
        // the triangles in increasing order.
        mFirst.assign(mDim[0] * mDim[1] * mDim[2] + 1, 0);
        auto forEachLeaf = [&](const VoxelRange& r, auto&& f) {
            for (int x = r.lo.x(); x <= r.hi.x(); ++x)
                for (int y = r.lo.y(); y <= r.hi.y(); ++y)
                    for (int z = r.lo.z(); z <= r.hi.z(); ++z) f(slot(openvdb::Coord(x, y, z)));
        };
        for (int t = 0; t < triangles; ++t) forEachLeaf(leavesOf(t), [&](size_t s) { ++mFirst[s + 1]; });
        for (size_t s = 1; s < mFirst.size(); ++s) mFirst[s] += mFirst[s - 1];
        mTriangles.resize(mFirst.back());
        std::vector<size_t> next(mFirst.begin(), mFirst.end() - 1);
        for (int t = 0; t < triangles; ++t)
            forEachLeaf(leavesOf(t), [&](size_t s) { mTriangles[next[s]++] = t; });
    }

    size_t leafCount() const { return mFirst.size() - 1; }
    /// The table's first leaf (in leaves) and its size, x-major.
    const openvdb::Coord& lowLeaf() const { return mLow; }
    const std::array<size_t, 3>& leafCounts() const { return mDim; }
    /// The first voxel of leaf @a s.
    openvdb::Coord leafOrigin(size_t s) const
    {
        const size_t yz = mDim[1] * mDim[2];
        const openvdb::Coord leaf(int(s / yz), int((s % yz) / mDim[2]), int(s % mDim[2]));
        return (leaf + mLow) << kLeafLog2;
    }
    const int* begin(size_t s) const { return mTriangles.data() + mFirst[s]; }
    const int* end(size_t s) const { return mTriangles.data() + mFirst[s + 1]; }

private:
    size_t slot(const openvdb::Coord& leaf) const
    {
        const openvdb::Coord l = leaf - mLow;
        return (size_t(l.x()) * mDim[1] + size_t(l.y())) * mDim[2] + size_t(l.z());
    }

    openvdb::Coord mLow;
    std::array<size_t, 3> mDim{};
    std::vector<size_t> mFirst;
    std::vector<int> mTriangles;
};

} // namespace

std::unique_ptr<closest::CodeGrid> meshNarrowBand(const TriangleMesh& mesh, const Vec3& origin,
                                                   double voxelSize, int exteriorBandVoxels)
{
    using namespace closest;
    const MeshPseudoNormals sides(mesh);
    constexpr double kInteriorBandVoxels = 2.0;
    const double reachVoxels = std::max(double(exteriorBandVoxels), kInteriorBandVoxels);
    const LeafTriangles bins(mesh, origin, voxelSize, reachVoxels);
    const double outsideReach2 = std::pow(exteriorBandVoxels * voxelSize, 2);
    const double insideReach2 = std::pow(kInteriorBandVoxels * voxelSize, 2);
    const double reach2 = std::max(outsideReach2, insideReach2);

    auto grid = std::make_unique<CodeGrid>(bins.lowLeaf(), bins.leafCounts());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, bins.leafCount(), 16),
                      [&](const tbb::blocked_range<size_t>& range) {
        std::array<double, CodeLeaf::kSize> best;
        std::array<int, CodeLeaf::kSize> nearest;
        std::array<openvdb::Int32, CodeLeaf::kSize> codes;
        std::array<bool, CodeLeaf::kSize> inBand;
        for (size_t s = range.begin(); s != range.end(); ++s) {
            if (bins.begin(s) == bins.end(s)) continue;
            const openvdb::Coord first = bins.leafOrigin(s);
            best.fill(std::numeric_limits<double>::infinity());
            nearest.fill(-1);
            // Each voxel's nearest triangle; the triangles come in increasing order, so a
            // strict "nearer" keeps the lowest-numbered of equally near ones.
            for (const int* t = bins.begin(s); t != bins.end(s); ++t) {
                const auto& tri = mesh.triangles[size_t(*t)];
                const Vec3 &a = mesh.vertices[size_t(tri[0])], &b = mesh.vertices[size_t(tri[1])],
                           &c = mesh.vertices[size_t(tri[2])];
                const VoxelRange r = reachOf(mesh, *t, origin, voxelSize, reachVoxels);
                openvdb::Coord lo, hi;
                for (int k = 0; k < 3; ++k) {
                    lo[k] = std::max(r.lo[k], first[k]) - first[k];
                    hi[k] = std::min(r.hi[k], first[k] + kLeafDim - 1) - first[k];
                }
                for (int x = lo.x(); x <= hi.x(); ++x)
                    for (int y = lo.y(); y <= hi.y(); ++y)
                        for (int z = lo.z(); z <= hi.z(); ++z) {
                            const Vec3 p = origin + voxelSize * Vec3(first.x() + x, first.y() + y,
                                                                     first.z() + z);
                            const double d2 = offsetFromTriangle(p, a, b, c).squaredNorm();
                            const int n = (x << (2 * kLeafLog2)) | (y << kLeafLog2) | z;
                            if (d2 < best[size_t(n)]) {
                                best[size_t(n)] = d2;
                                nearest[size_t(n)] = *t;
                            }
                        }
            }
            inBand.fill(false);
            bool any = false;
            for (int n = 0; n < CodeLeaf::kSize; ++n) {
                const int t = nearest[size_t(n)];
                if (t < 0 || !(best[size_t(n)] < reach2)) continue;  // in the band on no side
                const openvdb::Coord c = first + CodeLeaf::localCoord(n);
                const bool outside =
                    sides.isOutside(origin + voxelSize * Vec3(c.x(), c.y(), c.z()), t);
                if (!(best[size_t(n)] < (outside ? outsideReach2 : insideReach2))) continue;
                codes[size_t(n)] = bandCode(t, outside);
                inBand[size_t(n)] = any = true;
            }
            // Each thread fills slots of its own: the table does not change shape.
            if (any) grid->adopt(s, std::make_unique<CodeLeaf>(first, codes, inBand));
        }
    });
    return grid;
}

} // namespace lsdem
