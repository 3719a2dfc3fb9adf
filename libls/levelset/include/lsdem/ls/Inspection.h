/// @file Inspection.h
/// @brief Look inside a grain asset or any level-set .vdb: grid statistics, node statistics,
///        the level set's own area and volume (OpenVDB LevelSetMeasure), and quality measures.
#pragma once

#include "lsdem/ls/GrainAsset.h"

#include <memory>
#include <string>

namespace lsdem {

/// What lsdem-inspect opened: an lsdem asset (nodes, mass properties) or a bare level set.
struct InspectionTarget
{
    std::string path;
    std::shared_ptr<const GrainAsset> asset;          ///< null for a foreign level set
    std::shared_ptr<const LevelSetGrid> levelSet;     ///< always set
    std::string gridName;
};

/// Open @a path: an lsdem asset if it is one, otherwise its first float grid of class level
/// set (or, failing that, its first float grid). An asset is read by loadAsset, its seal
/// checked before OpenVDB reads it.
/// @throw Error if the file is missing, not a .vdb, or holds no float grid, or as loadAsset
/// throws for an asset (damaged, unsealed).
InspectionTarget openForInspection(const std::string& path);

struct InspectionReport
{
    // Grid.
    std::array<int, 3> indexMin{}, indexMax{};  ///< active voxel bounding box, index space
    Vec3 worldMin = Vec3::Zero(), worldMax = Vec3::Zero();
    double voxelSize = 0.0;
    long long activeVoxels = 0;
    double memoryBytes = 0.0;      ///< OpenVDB's memUsage of the grid
    double denseBytes = 0.0;       ///< a dense float grid over the same bounding box
    double background = 0.0;
    // Level set's own measures (OpenVDB LevelSetMeasure).
    double levelSetArea = 0.0, levelSetVolume = 0.0;
    // Quality.
    double bandGradientOffShare = 0.0;  ///< share of band voxels with ||∇φ| - 1| > 10 %
    long long bandVoxels = 0;
    // Nodes (assets only).
    size_t nodeCount = 0;
    NodeSpacing spacing;
    double nodeAreaSum = 0.0;
    double maxAbsPhiAtNodesVoxels = 0.0;  ///< max |φ| at the nodes, in voxels
};

InspectionReport inspect(const InspectionTarget& target);

/// The zero isosurface of the level set (OpenVDB volumeToMesh), quads split into triangles.
/// @a meshVoxel larger than the grid's voxel meshes a copy rebuilt at that voxel size instead:
/// a lighter surface for pictures and ParaView frames (a fine grain can have 10⁵ triangles).
TriangleMesh zeroIsosurface(const LevelSetGrid& levelSet, double meshVoxel = 0.0);

} // namespace lsdem
