#include "lsdem/ls/MeshLevelSet.h"

#include "ClosestTriangleGrid.h"
#include "MeshNarrowBand.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/OrderedCollect.h"
#include "lsdem/core/ReleaseMemory.h"
#include "lsdem/mesh/TriangleOffset.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <vector>

namespace lsdem {

namespace {

using closest::CodeGrid;
using closest::CodeLeaf;

const openvdb::Coord kFaces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

/// The inward propagation of closest triangles: each voxel inside the band takes the nearest
/// of the triangles closest to its 26 neighbours, layer after layer inward from the band.
/// Works in the caller's grid of codes (ClosestTriangleGrid.h), which holds the band: the
/// distances are made from the codes only as the bricks are written, so no float tree of them
/// all is ever held.
///
/// What is inside is found by the fill itself: the voxels not in the band (inactive) that are
/// face-adjacent to the band's inside, and to those, and so on. A voxel face-adjacent to one
/// less than two voxels inside is less than three inside (the distance changes by at most a
/// voxel from one to the next), so it cannot lie outside the band (at least two outside):
/// the fill never leaves the inside. (A mesh that crosses itself has no inside, and its
/// pseudo-normals can disagree: the fill is then kept within the band's box.)
class InteriorFill
{
public:
    InteriorFill(CodeGrid& codes, const TriangleMesh& mesh, const Vec3& origin,
                 double voxelSize)
        : mClosest(codes), mMesh(mesh), mOrigin(origin), mVoxel(voxelSize),
          mBounds(codes.activeBox())
    {
    }

    /// Find the closest triangle of every voxel inside beyond the band, layer after layer
    /// inward from the band's inside voxels that touch one.
    void run()
    {
        // The layers' lists kept from one layer to the next: freed and made again each time,
        // they left holes that the leaves made meanwhile split, and the heap grew past them
        // (by 3 times the codes on a small grid, docs/assets.md).
        std::vector<openvdb::Coord> layer = bandEdge(), next;
        std::vector<openvdb::Int32> nearest;
        while (!layer.empty()) {
            nextLayer(layer, next);
            std::swap(layer, next);
            solveLayer(layer, nearest);
        }
    }

private:
    /// Whether the voxel at @a c is yet to be reached: not in the band nor filled, and within
    /// the band's box.
    bool isUnknown(const openvdb::Coord& c) const
    {
        return mBounds.isInside(c) && !mClosest.isOn(c);
    }

    /// The band's inside voxels with an unknown face neighbour, leaf by leaf in the table's
    /// order: the first layer (every solved face neighbour of an unknown voxel is among them).
    std::vector<openvdb::Coord> bandEdge() const
    {
        auto touchingUnknown = [&](size_t begin, size_t end, std::vector<openvdb::Coord>& out) {
            for (size_t slot = begin; slot < end; ++slot) {
                const CodeLeaf* leaf = mClosest.leafAtSlot(slot);
                if (!leaf) continue;
                leaf->forEachOn([&](int n, openvdb::Int32 code) {
                    if (!closest::holdsTriangle(code) || closest::isOutside(code)) return;
                    const openvdb::Coord c = leaf->origin() + CodeLeaf::localCoord(n);
                    for (const openvdb::Coord& step : kFaces)
                        if (isUnknown(c + step)) {
                            out.push_back(c);
                            break;
                        }
                });
            }
        };
        return collectInOrder<openvdb::Coord>(mClosest.slotCount(), 64, touchingUnknown);
    }

    /// Into @a next, the unknown voxels face-adjacent to @a layer, each once, in an order set by the layer's
    /// alone (the same on any thread count). Found in parallel without marking: an unknown
    /// voxel's solved face neighbours all belong to the last layer (each earlier layer's
    /// unknown neighbours went into the layer after it), and the first of them in kFaces order
    /// is the one that adds it.
    void nextLayer(const std::vector<openvdb::Coord>& layer, std::vector<openvdb::Coord>& next) const
    {
        auto unknownNeighbours = [&](size_t begin, size_t end, std::vector<openvdb::Coord>& out) {
            // Whether @a c is the first solved face neighbour of @a n in kFaces order.
            auto addsIt = [&](const openvdb::Coord& c, const openvdb::Coord& n) {
                for (const openvdb::Coord& back : kFaces) {
                    const openvdb::Coord m = n + back;
                    if (m == c) return true;
                    if (mClosest.isOn(m)) return false;
                }
                return true;
            };
            for (size_t i = begin; i < end; ++i) {
                const openvdb::Coord& c = layer[i];
                for (const openvdb::Coord& step : kFaces) {
                    const openvdb::Coord n = c + step;
                    if (!isUnknown(n)) continue;
                    if (addsIt(c, n)) out.push_back(n);
                }
            }
        };
        collectInOrder<openvdb::Coord>(layer.size(), 2048, unknownNeighbours, next);
    }

    /// The codes of the 27 voxels around @a c (itself included).
    void neighbourhood(const openvdb::Coord& c, openvdb::Int32 out[27]) const
    {
        // Away from its leaf's faces a voxel's neighbours are all in its leaf: read them there
        // (offsets x*64 + y*8 + z) instead of finding the leaf 27 times.
        constexpr int kLast = CodeLeaf::kDim - 1;
        const int x = c.x() & kLast, y = c.y() & kLast, z = c.z() & kLast;
        if (x > 0 && x < kLast && y > 0 && y < kLast && z > 0 && z < kLast) {
            if (const CodeLeaf* leaf = mClosest.leaf(c)) {
                const int centre = CodeLeaf::offset(c);
                constexpr int dx = CodeLeaf::kDim * CodeLeaf::kDim, dy = CodeLeaf::kDim;
                int k = 0;
                for (int i = -1; i <= 1; ++i)
                    for (int j = -1; j <= 1; ++j)
                        for (int l = -1; l <= 1; ++l)
                            out[k++] = leaf->code(centre + i * dx + j * dy + l);
                return;
            }
        }
        int k = 0;
        for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j)
                for (int l = -1; l <= 1; ++l) out[k++] = mClosest.code(c.offsetBy(i, j, l));
    }

    double squaredDistance(const Vec3& p, openvdb::Int32 t) const
    {
        return offsetFromTriangle(p, mMesh, t).squaredNorm();
    }

    Vec3 centre(const openvdb::Coord& c) const
    {
        return mOrigin + mVoxel * Vec3(c.x(), c.y(), c.z());
    }

    /// Each voxel of @a layer takes the nearest of the triangles closest to itself and its 26
    /// neighbours (ties to the lower index); the voxels of one layer are independent.
    /// @a nearest: room for the results, kept from layer to layer.
    void solveLayer(const std::vector<openvdb::Coord>& layer, std::vector<openvdb::Int32>& nearest)
    {
        nearest.resize(layer.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, layer.size(), 512),
                          [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                const Vec3 p = centre(layer[i]);
                openvdb::Int32 around[27];
                neighbourhood(layer[i], around);
                double best = std::numeric_limits<double>::infinity();
                openvdb::Int32 bestTriangle = closest::kNoTriangle;
                // The 27 hold a few distinct triangles, each many times: a triangle already
                // tried is skipped by a look in a small table by its low bits. Two sharing a
                // slot are both tried, which costs time only: the nearest (ties to the lower
                // index) does not depend on the order or on repeats.
                openvdb::Int32 tried[32];
                std::fill(std::begin(tried), std::end(tried), -1);
                for (openvdb::Int32 code : around) {
                    if (!closest::holdsTriangle(code)) continue;
                    const openvdb::Int32 t = closest::triangleOf(code);
                    openvdb::Int32& slot = tried[t & 31];
                    if (slot == t) continue;
                    slot = t;
                    const double d2 = squaredDistance(p, t);
                    if (d2 < best || (d2 == best && t < bestTriangle)) {
                        best = d2;
                        bestTriangle = t;
                    }
                }
                nearest[i] = bestTriangle;  // (an inside code: no band bit)
            }
        });
        // Written once the whole layer is solved (its voxels read each other's old values),
        // on one thread: leaves are made, and a leaf's codes and active states are shared.
        for (size_t i = 0; i < layer.size(); ++i) mClosest.set(layer[i], nearest[i]);
    }

    CodeGrid& mClosest;
    const TriangleMesh& mMesh;
    Vec3 mOrigin;
    double mVoxel;
    openvdb::CoordBBox mBounds;  ///< the band's box: the inside lies within it
};

/// The bricks' values from the codes: each voxel's distance to its closest triangle, minus it
/// inside; inactive voxels (all outside) at the background. The codes' leaves are freed as the
/// bricks are written past them, and their pages handed back, so the codes and the bricks are
/// not all held at once.
class ClosestTriangleSource : public LevelSetBricks::Source
{
public:
    ClosestTriangleSource(CodeGrid& codes, const TriangleMesh& mesh, const Vec3& origin,
                          double voxelSize, float background)
        : mCodes(codes), mMesh(mesh), mOrigin(origin), mVoxel(voxelSize), mBackground(background)
    {
    }

    void releaseBelow(int x) override
    {
        // The leaves are small blocks inside malloc's heaps, which keeps them; the pages they
        // leave wholly free go back to the system, for the bricks' storage to take.
        if (mCodes.releaseBelow(x) > 0) releaseFreedMemory();
    }

    openvdb::CoordBBox valueBox() const override { return mCodes.activeBox(); }

    class Reader : public LevelSetBricks::Source::Reader
    {
    public:
        explicit Reader(const ClosestTriangleSource& source) : mSource(source) {}

        void read(const openvdb::Coord& origin, LevelSetBricks::RawBrick& raw) override
        {
            constexpr int kDim = LevelSetBricks::kDim;
            std::fill(std::begin(raw.active), std::end(raw.active), 0);
            for (int x = 0; x < kDim; ++x)
                for (int y = 0; y < kDim; ++y)
                    for (int z = 0; z < kDim; ++z) {
                        const openvdb::Coord c = origin.offsetBy(x, y, z);
                        const int k = LevelSetBricks::offset(openvdb::Coord(x, y, z));
                        const openvdb::Int32 code = mSource.mCodes.code(c);
                        if (code == closest::kOutside) {  // (inactive)
                            raw.value[k] = mSource.mBackground;
                            continue;
                        }
                        raw.active[k >> 6] |= uint64_t(1) << (k & 63);
                        raw.value[k] = mSource.distance(c, code);
                    }
        }

    private:
        const ClosestTriangleSource& mSource;
    };

    std::unique_ptr<LevelSetBricks::Source::Reader> reader() const override
    {
        return std::make_unique<Reader>(*this);
    }

private:
    /// The signed distance at the active voxel @a c of code @a code.
    float distance(const openvdb::Coord& c, openvdb::Int32 code) const
    {
        if (!closest::holdsTriangle(code)) return -mBackground;  // never reached by the fill
        const Vec3 p = mOrigin + mVoxel * Vec3(c.x(), c.y(), c.z());
        const auto depth = float(offsetFromTriangle(p, mMesh, closest::triangleOf(code)).norm());
        return closest::isOutside(code) ? depth : -depth;
    }

    CodeGrid& mCodes;
    const TriangleMesh& mMesh;
    Vec3 mOrigin;
    double mVoxel;
    float mBackground;
};

} // namespace

std::shared_ptr<LevelSetGrid> meshLevelSet(const TriangleMesh& mesh, double voxelSize,
                                           int exteriorBandVoxels)
{
    initializeOpenVdb();
    if (exteriorBandVoxels < kMinExteriorBandVoxels)
        throw Error("", "the exterior band must be at least " +
                            std::to_string(kMinExteriorBandVoxels) + " voxels wide, got " +
                            std::to_string(exteriorBandVoxels),
                    "interpolation near the surface reads values up to 1.73 voxels outside it");
    if (mesh.triangles.size() >= closest::kMaxTriangles)
        throw Error("", "the mesh has " + std::to_string(mesh.triangles.size()) +
                            " triangles; the level set takes fewer than 2^29",
                    "simplify the mesh (a grain needs far fewer triangles than its voxels)");
    const auto bounds = meshBounds(mesh);
    const double vox = voxelSize;
    const double pad = (exteriorBandVoxels + 2) * vox;
    Vec3 origin;
    for (int k = 0; k < 3; ++k) origin[k] = vox * std::floor((bounds[0][k] - pad) / vox);

    // 1. The narrow band: exact distances within the exterior band and two voxels inside, as
    //    each voxel's nearest triangle and side (MeshNarrowBand.h).
    const std::unique_ptr<CodeGrid> codes =
        meshNarrowBand(mesh, origin, vox, exteriorBandVoxels);
    //    What the band's search freed (its bins and pseudo-normals) goes back for the fill.
    releaseFreedMemory();
    // 2. The inside: each voxel reached by the fill inward from the band (InteriorFill).
    InteriorFill(*codes, mesh, origin, vox).run();

    // 3. The bricks, their values made from the codes as they are read.
    const auto background = float(exteriorBandVoxels * vox);
    openvdb::FloatGrid header(background);
    header.setTransform(makeGridTransform(vox, origin));
    header.setGridClass(openvdb::GRID_LEVEL_SET);
    auto levelSet = std::make_shared<LevelSetGrid>();
    levelSet->grid = std::make_shared<const LevelSetBricks>(
        header, ClosestTriangleSource(*codes, mesh, origin, vox, background));
    levelSet->origin = origin;
    levelSet->voxelSize = vox;
    return levelSet;
}

} // namespace lsdem
