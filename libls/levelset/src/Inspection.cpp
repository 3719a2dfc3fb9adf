#include "lsdem/ls/Inspection.h"

#include "AssetChecksum.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <filesystem>

namespace lsdem {

InspectionTarget openForInspection(const std::string& path)
{
    initializeOpenVdb();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error(path, "no such file", "check the path");
    InspectionTarget target;
    target.path = path;
    // OpenVDB trusts the sizes a file states, so a damaged asset could crash it: an asset goes
    // through loadAsset, which checks its seal before OpenVDB reads it.
    if (claimsToBeAsset(path)) {
        target.asset = loadAsset(path);
        target.levelSet = target.asset->levelSet;
        target.gridName = "phi";
        return target;
    }
    openvdb::GridPtrVecPtr grids;
    try {
        openvdb::io::File file(path);
        file.open(false);
        grids = file.getGrids();
        file.close();
    } catch (const std::exception& e) {
        throw Error(path, std::string("not a readable OpenVDB file (") + e.what() + ")",
                    "the file is corrupt or not a .vdb");
    }
    openvdb::FloatGrid::Ptr chosen;
    for (const auto& grid : *grids) {
        auto floatGrid = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
        if (!floatGrid) continue;
        if (!chosen || (chosen->getGridClass() != openvdb::GRID_LEVEL_SET &&
                        floatGrid->getGridClass() == openvdb::GRID_LEVEL_SET))
            chosen = floatGrid;
    }
    if (!chosen) throw Error(path, "holds no float grid to inspect");
    const auto& xform = chosen->transform();
    if (!xform.isLinear() || !xform.hasUniformScale())
        throw Error(path, "grid '" + chosen->getName() + "' has a non-uniform or non-linear "
                          "transform, which lsdem cannot sample");
    auto levelSet = std::make_shared<LevelSetGrid>();
    levelSet->voxelSize = xform.voxelSize()[0];
    const openvdb::Vec3d o = xform.indexToWorld(openvdb::Vec3d(0, 0, 0));
    levelSet->origin = Vec3(o.x(), o.y(), o.z());
    levelSet->grid = toLevelSetGrid(*chosen);
    target.levelSet = levelSet;
    target.gridName = chosen->getName();
    return target;
}

InspectionReport inspect(const InspectionTarget& target)
{
    const LevelSetGrid& ls = *target.levelSet;
    // OpenVDB's tools are instantiated for the standard tree: inspect a copy in it.
    const openvdb::FloatGrid::Ptr standard = toFloatGrid(*ls.grid);
    const openvdb::FloatGrid& grid = *standard;
    InspectionReport r;
    r.voxelSize = ls.voxelSize;
    r.activeVoxels = static_cast<long long>(grid.activeVoxelCount());
    r.memoryBytes = static_cast<double>(ls.grid->memUsage());  // as held in memory
    r.background = grid.background();
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    for (int k = 0; k < 3; ++k) {
        r.indexMin[k] = box.min()[k];
        r.indexMax[k] = box.max()[k];
        r.worldMin[k] = ls.origin[k] + ls.voxelSize * box.min()[k];
        r.worldMax[k] = ls.origin[k] + ls.voxelSize * box.max()[k];
    }
    r.denseBytes = 4.0 * static_cast<double>(box.volume());

    if (grid.getGridClass() == openvdb::GRID_LEVEL_SET) {
        openvdb::tools::LevelSetMeasure<openvdb::FloatGrid> measure(grid);
        r.levelSetArea = measure.area(/*useWorldUnits=*/true);
        r.levelSetVolume = measure.volume(/*useWorldUnits=*/true);
    }

    // Gradient quality by central differences, over active voxels closer to the surface than
    // the exterior band width whose six neighbours are active too (deeper interior voxels
    // are distances as well, but the band is where contacts happen).
    const double band = std::abs(r.background);
    auto accessor = grid.getConstAccessor();
    long long off = 0;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue() || std::abs(*it) >= band) continue;
        const openvdb::Coord c = it.getCoord();
        openvdb::Vec3d g;
        bool complete = true;  // a neighbour beyond the band holds the clamped background
        for (int k = 0; k < 3 && complete; ++k) {
            openvdb::Coord plus = c, minus = c;
            plus[k] += 1;
            minus[k] -= 1;
            complete = accessor.isValueOn(plus) && accessor.isValueOn(minus);
            g[k] = (accessor.getValue(plus) - accessor.getValue(minus)) / (2.0 * ls.voxelSize);
        }
        if (!complete) continue;
        ++r.bandVoxels;
        if (std::abs(g.length() - 1.0) > 0.1) ++off;
    }
    r.bandGradientOffShare = r.bandVoxels ? double(off) / double(r.bandVoxels) : 0.0;

    if (target.asset) {
        const GrainAsset& a = *target.asset;
        r.nodeCount = a.nodes.size();
        r.spacing = a.spacing;
        r.nodeAreaSum = a.nodes.totalArea();
        LevelSetSampler sampler(ls);
        for (const Vec3& p : a.nodes.positions)
            r.maxAbsPhiAtNodesVoxels =
                std::max(r.maxAbsPhiAtNodesVoxels, std::abs(sampler.phi(p)) / ls.voxelSize);
    }
    return r;
}

TriangleMesh zeroIsosurface(const LevelSetGrid& levelSet, double meshVoxel)
{
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    const openvdb::FloatGrid::Ptr standard = toFloatGrid(*levelSet.grid);
    if (meshVoxel > levelSet.voxelSize) {
        const auto coarse = openvdb::math::Transform::createLinearTransform(meshVoxel);
        const openvdb::FloatGrid::Ptr rebuilt =
            openvdb::tools::levelSetRebuild(*standard, 0.0f, 2.0f, coarse.get());
        openvdb::tools::volumeToMesh(*rebuilt, points, triangles, quads, 0.0, 0.0);
    } else {
        openvdb::tools::volumeToMesh(*standard, points, triangles, quads, 0.0, 0.0);
    }
    TriangleMesh mesh;
    for (const auto& p : points) mesh.vertices.emplace_back(p.x(), p.y(), p.z());
    // OpenVDB emits faces clockwise seen from outside (for negative-inside level sets);
    // reverse them so lsdem's counter-clockwise convention holds.
    for (const auto& t : triangles) mesh.triangles.push_back({int(t[2]), int(t[1]), int(t[0])});
    for (const auto& q : quads) {
        mesh.triangles.push_back({int(q[2]), int(q[1]), int(q[0])});
        mesh.triangles.push_back({int(q[3]), int(q[2]), int(q[0])});
    }
    return mesh;
}

} // namespace lsdem
