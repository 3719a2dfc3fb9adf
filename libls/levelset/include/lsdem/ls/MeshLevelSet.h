/// @file MeshLevelSet.h
/// @brief The signed distance to a closed mesh on a sparse grid whose index space lies in the
///        positive octant: the level-set stage of baking a mesh (see docs/assets.md).
///        Heavy header (OpenVDB): include it only where grids are built.
#pragma once

#include "lsdem/ls/GrainAsset.h"
#include "lsdem/ls/LevelSetGrid.h"

#include <memory>

namespace lsdem {

/// Signed distance to @a mesh (closed, consistently oriented, outward), negative inside, at
/// every voxel within @a exteriorBandVoxels outside the surface and at every voxel inside it.
/// The grid's index (0,0,0) is the lower corner of the mesh's bounds padded by the band and
/// two voxels. Throws lsdem::Error for a band under kMinExteriorBandVoxels, 2^29 triangles or
/// more, or an edge not shared by exactly two triangles running along it both ways.
std::shared_ptr<LevelSetGrid> meshLevelSet(const TriangleMesh& mesh, double voxelSize,
                                           int exteriorBandVoxels);

} // namespace lsdem
