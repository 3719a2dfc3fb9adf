/// @file LevelSetGrid.h
/// @brief The OpenVDB side of a grain asset: a float grid of class level set whose index space
///        lies in the positive octant (world = origin + voxelSize * index).
///        Heavy header (OpenVDB): include it only where grids are built, sampled or written.
#pragma once

#include "lsdem/ls/TriangleMesh.h"

#include <openvdb/openvdb.h>

namespace lsdem {

/// The tree of a grain's level set in memory: under the root, one level of 16³ internal nodes
/// (128 voxels wide) over the 8³ float leaves. OpenVDB's FloatTree puts a 32³ node (4096 voxels
/// wide, 264 KiB) above that, which a grain of a few hundred voxels pays in full. The leaves
/// are the same, so sampling reads the same buffers. Files hold a standard FloatGrid, which
/// vdb_print and every OpenVDB reader know: see toLevelSetGrid and toFloatGrid.
using LevelSetTree = openvdb::tree::Tree<openvdb::tree::RootNode<
    openvdb::tree::InternalNode<openvdb::tree::LeafNode<float, 3>, 4>>>;
using LevelSetFloatGrid = openvdb::Grid<LevelSetTree>;

struct LevelSetGrid
{
    LevelSetFloatGrid::Ptr grid;  ///< background = +exterior band width (length units)
    Vec3 origin = Vec3::Zero();    ///< world position of index (0,0,0)
    double voxelSize = 0.0;
};

/// @a grid's values, states, transform and metadata in a LevelSetTree; its leaves are moved,
/// not copied, so @a grid is left empty.
LevelSetFloatGrid::Ptr toLevelSetGrid(openvdb::FloatGrid& grid);

/// A copy of @a grid as a standard FloatGrid (for files and OpenVDB's tools).
openvdb::FloatGrid::Ptr toFloatGrid(const LevelSetFloatGrid& grid);

/// Initialise OpenVDB once per process (idempotent, thread-safe).
void initializeOpenVdb();

/// The box (in the asset frame) of the voxels of @a levelSet with φ < 0, widened by one voxel:
/// a trilinear sample can only be negative inside it. An empty box (min > max) if no voxel is
/// negative.
void insideBox(const LevelSetGrid& levelSet, Vec3& min, Vec3& max);

/// A linear transform with the given voxel size whose index (0,0,0) sits at @a origin.
openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin);

} // namespace lsdem
