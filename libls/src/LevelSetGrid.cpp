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

double levelSetSlopeBound(const LevelSetGrid& levelSet)
{
    const LevelSetBricks& grid = *levelSet.grid;
    const openvdb::CoordBBox table = grid.tableBox();
    if (table.empty()) return 0.0;  // the background everywhere: flat
    // Every edge with a voxel in the table, including those to the background around it.
    const openvdb::Coord lo = table.min().offsetBy(-1), hi = table.max();
    const double largest = tbb::parallel_reduce(
        tbb::blocked_range<int>(lo.x(), hi.x() + 1), 0.0,
        [&](const tbb::blocked_range<int>& xs, double found) {
            for (int x = xs.begin(); x != xs.end(); ++x)
                for (int y = lo.y(); y <= hi.y(); ++y)
                    for (int z = lo.z(); z <= hi.z(); ++z) {
                        const openvdb::Coord c(x, y, z);
                        const double v = grid.value(c);
                        found = std::max({found, std::abs(grid.value(c.offsetBy(1, 0, 0)) - v),
                                          std::abs(grid.value(c.offsetBy(0, 1, 0)) - v),
                                          std::abs(grid.value(c.offsetBy(0, 0, 1)) - v)});
                    }
            return found;
        },
        [](double a, double b) { return std::max(a, b); });
    return std::sqrt(3.0) * largest / levelSet.voxelSize;
}

void deriveContactBounds(GrainAsset& asset)
{
    asset.nodeBlocks = groupNodesIntoBlocks(asset.nodes);
    insideBox(*asset.levelSet, asset.insideBoxMin, asset.insideBoxMax);
    asset.levelSetSlope = levelSetSlopeBound(*asset.levelSet);
}

openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin)
{
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
    return xform;
}

} // namespace lsdem
