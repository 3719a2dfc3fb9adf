#include "lsdem/ls/LevelSetGrid.h"

#include <limits>
#include <mutex>
#include <vector>

namespace lsdem {

namespace {

/// Copy the tiles of @a from (not its leaves' voxels) into @a to, and its transform and
/// metadata; values equal to the background in inactive tiles are left to the background.
template <typename FromGrid, typename ToGrid>
void copyTilesAndMetadata(const FromGrid& from, ToGrid& to)
{
    static_cast<openvdb::MetaMap&>(to) = static_cast<const openvdb::MetaMap&>(from);
    to.setTransform(from.transform().copy());
    auto it = from.tree().cbeginValueAll();
    it.setMaxDepth(FromGrid::TreeType::RootNodeType::LEVEL - 1);  // tiles only, no voxels
    for (; it; ++it)
        if (it.isValueOn() || *it != from.background())
            to.tree().fill(it.getBoundingBox(), *it, it.isValueOn());
}

} // namespace

LevelSetFloatGrid::Ptr toLevelSetGrid(openvdb::FloatGrid& grid)
{
    auto result = LevelSetFloatGrid::create(grid.background());
    copyTilesAndMetadata(grid, *result);
    std::vector<openvdb::FloatTree::LeafNodeType*> leaves;
    leaves.reserve(grid.tree().leafCount());
    grid.tree().stealNodes(leaves);
    for (auto* leaf : leaves) result->tree().addLeaf(leaf);  // takes ownership
    grid.tree().clear();
    return result;
}

openvdb::FloatGrid::Ptr toFloatGrid(const LevelSetFloatGrid& grid)
{
    auto result = openvdb::FloatGrid::create(grid.background());
    copyTilesAndMetadata(grid, *result);
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf)
        result->tree().addLeaf(new openvdb::FloatTree::LeafNodeType(*leaf));
    return result;
}

void initializeOpenVdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void insideBox(const LevelSetGrid& levelSet, Vec3& min, Vec3& max)
{
    openvdb::CoordBBox box;  // empty
    // Active voxels and tiles; the interior is filled, and inactive values outside it are the
    // positive background.
    for (auto it = levelSet.grid->cbeginValueOn(); it; ++it)
        if (*it < 0.0f) box.expand(it.getBoundingBox());
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

openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin)
{
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
    return xform;
}

} // namespace lsdem
