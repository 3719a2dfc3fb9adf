#include "lsdem/ls/LevelSetGrid.h"

#include "lsdem/ls/GrainAsset.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

namespace lsdem {

std::shared_ptr<const LevelSetBricks> toLevelSetGrid(const openvdb::FloatGrid& grid)
{
    return std::make_shared<const LevelSetBricks>(grid);
}

openvdb::FloatGrid::Ptr toFloatGrid(const LevelSetBricks& grid) { return grid.toFloatGrid(); }

void initializeOpenVdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void insideBox(const LevelSetGrid& levelSet, Vec3& min, Vec3& max)
{
    openvdb::CoordBBox box;  // empty
    // Active voxels and bricks; the interior is filled, and inactive values outside it are the
    // positive background.
    levelSet.grid->forEachBrick(
        [&](const openvdb::Coord& c, float value, bool active) {
            if (active && value < 0.0f) box.expand(c);
        },
        [&](const openvdb::CoordBBox& brick, float value, bool active) {
            if (active && value < 0.0f) box.expand(brick);
        });
    if (box.empty()) {
        min = Vec3::Constant(std::numeric_limits<double>::infinity());
        max = -min;
        return;
    }
    const double h = levelSet.voxelSize;
    const openvdb::Coord lo = box.min(), hi = box.max();
    min = levelSet.origin + h * Vec3(lo.x() - 1, lo.y() - 1, lo.z() - 1);
    max = levelSet.origin + h * Vec3(hi.x() + 1, hi.y() + 1, hi.z() + 1);
}

namespace {

/// The slope bound of one cell whose corner (i, j, k) ∈ {0, 1}³ has the value @a corner(i, j, k),
/// if some corner is at φ ≥ 0, else 0: the root of the sum of the squares of the largest
/// difference along each axis.
template <typename Corner> double cellSlope(Corner&& corner)
{
    double v[2][2][2];
    bool anyOutside = false;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) {
                v[i][j][k] = corner(i, j, k);
                anyOutside |= v[i][j][k] >= 0.0;
            }
    if (!anyOutside) return 0.0;
    double dx = 0.0, dy = 0.0, dz = 0.0;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            dx = std::max(dx, std::abs(v[1][a][b] - v[0][a][b]));
            dy = std::max(dy, std::abs(v[a][1][b] - v[a][0][b]));
            dz = std::max(dz, std::abs(v[a][b][1] - v[a][b][0]));
        }
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// The largest slope bound of a cell (below) whose lower corner is a voxel of the 4³ place
/// whose brick is @a bricks[0][0][0] and that has a corner at φ ≥ 0, in value units per voxel;
/// the corners after the place are read from the bricks after it (@a bricks[i][j][k] is the
/// brick i, j, k places further along x, y, z).
///
/// In a cell the trilinear interpolant's derivative along x is, at every point, a weighted
/// mean of the cell's four differences along x; so |∇φ| there is at most the root of the sum
/// of the squares of the largest difference along each axis.
double largestCellSlopeFromPlace(const LevelSetBricks& grid, const uint32_t (&bricks)[2][2][2])
{
    constexpr int kDim = LevelSetBricks::kDim, kWindow = kDim + 1;
    float window[kWindow][kWindow][kWindow];
    for (int x = 0; x < kWindow; ++x)
        for (int y = 0; y < kWindow; ++y)
            for (int z = 0; z < kWindow; ++z)
                window[x][y][z] = grid.decode(bricks[x / kDim][y / kDim][z / kDim],
                                              LevelSetBricks::offset(openvdb::Coord(x, y, z)));
    double largest = 0.0;
    for (int x = 0; x < kDim; ++x)
        for (int y = 0; y < kDim; ++y)
            for (int z = 0; z < kDim; ++z)
                largest = std::max(largest, cellSlope([&](int i, int j, int k) {
                                       return double(window[x + i][y + j][z + k]);
                                   }));
    return largest;
}

} // namespace

double levelSetSlopeBound(const LevelSetGrid& levelSet)
{
    const LevelSetBricks& grid = *levelSet.grid;
    const openvdb::CoordBBox table = grid.tableBox();
    if (table.empty()) return 0.0;  // the background everywhere: flat
    // Every cell with a corner in the table, including those reaching into the background
    // around it, has its lower corner in a place of the table or of the layer of places before
    // it; its window is the place's voxels and one more voxel along +x, +y and +z, read from
    // at most 8 bricks. A window of one shared brick (the background, an interior tile) holds
    // one value and no slope.
    constexpr int kDim = LevelSetBricks::kDim;
    const openvdb::Coord extent = table.dim();  // voxels, whole bricks
    const openvdb::Coord places(extent.x() / kDim, extent.y() / kDim, extent.z() / kDim);
    const double largest = tbb::parallel_reduce(
        tbb::blocked_range<int>(-1, places.x()), 0.0,
        [&](const tbb::blocked_range<int>& bxs, double found) {
            for (int bx = bxs.begin(); bx != bxs.end(); ++bx)
                for (int by = -1; by < places.y(); ++by)
                    for (int bz = -1; bz < places.z(); ++bz) {
                        uint32_t bricks[2][2][2];
                        bool oneBrick = true, allDeep = true;
                        for (int i = 0; i < 2; ++i)
                            for (int j = 0; j < 2; ++j)
                                for (int k = 0; k < 2; ++k) {
                                    bricks[i][j][k] = grid.brick(bx + i, by + j, bz + k);
                                    oneBrick &= bricks[i][j][k] == bricks[0][0][0];
                                    allDeep &= grid.isDeep(bricks[i][j][k]);
                                }
                        // A varying brick is at one place only, so 8 equal ones are shared;
                        // deep bricks lie wholly inside, where no cell counts.
                        if (!oneBrick && !allDeep)
                            found = std::max(found, largestCellSlopeFromPlace(grid, bricks));
                    }
            return found;
        },
        [](double a, double b) { return std::max(a, b); });
    return largest / levelSet.voxelSize;
}

GrainAsset withExactDistance(GrainAsset asset, std::shared_ptr<const ExactDistance> distance)
{
    auto levelSet = std::make_shared<LevelSetGrid>(*asset.levelSet);
    levelSet->exact = std::move(distance);
    asset.levelSet = levelSet;
    deriveContactBounds(asset);
    return asset;
}

void deriveContactBounds(GrainAsset& asset)
{
    asset.nodeBlocks = groupNodesIntoBlocks(asset.nodes);
    insideBox(*asset.levelSet, asset.insideBoxMin, asset.insideBoxMax);
    asset.levelSetSlope = levelSetSlopeBound(*asset.levelSet);
    // A closed-form distance has slope 1 (the voxels' bound is about 1, maybe a hair under).
    if (asset.levelSet->exact) asset.levelSetSlope = std::max(asset.levelSetSlope, 1.0);
}

openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin)
{
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
    return xform;
}

} // namespace lsdem
