/// @file LevelSetGrid.h
/// @brief The OpenVDB side of a grain asset: a FloatGrid of class level set whose index space
///        lies in the positive octant (world = origin + voxelSize * index).
///        Heavy header (OpenVDB): include it only where grids are built, sampled or written.
#pragma once

#include "lsdem/ls/TriangleMesh.h"

#include <openvdb/openvdb.h>

namespace lsdem {

struct LevelSetGrid
{
    openvdb::FloatGrid::Ptr grid;  ///< background = +exterior band width (length units)
    Vec3 origin = Vec3::Zero();    ///< world position of index (0,0,0)
    double voxelSize = 0.0;
};

/// Initialise OpenVDB once per process (idempotent, thread-safe).
void initializeOpenVdb();

/// The box (in the asset frame) of the voxels of @a levelSet with φ < 0, widened by one voxel:
/// a trilinear sample can only be negative inside it. An empty box (min > max) if no voxel is
/// negative.
void insideBox(const LevelSetGrid& levelSet, Vec3& min, Vec3& max);

/// A linear transform with the given voxel size whose index (0,0,0) sits at @a origin.
openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin);

} // namespace lsdem
