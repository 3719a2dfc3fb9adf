/// @file LevelSetGrid.h
/// @brief The OpenVDB side of a grain asset: a level set whose index space lies in the
///        positive octant (world = origin + voxelSize * index), held compactly in memory and
///        as a standard FloatGrid of class level set in files.
///        Heavy header (OpenVDB): include it only where grids are built, sampled or written.
#pragma once

#include "lsdem/ls/ExactDistance.h"
#include "lsdem/ls/LevelSetBricks.h"
#include "lsdem/core/Vec3.h"

#include <openvdb/openvdb.h>

#include <memory>

namespace lsdem {

struct LevelSetGrid
{
    /// The values, 24-bit in 4³ bricks (16-bit deep inside; see LevelSetBricks.h); background = +exterior band
    /// width (length units). Shared, never modified.
    std::shared_ptr<const LevelSetBricks> grid;
    Vec3 origin = Vec3::Zero();    ///< world position of index (0,0,0)
    double voxelSize = 0.0;
    /// If set, the samplers return this closed-form distance instead of interpolating the
    /// voxels (ExactDistance.h: reference fixtures); the voxels still bound where φ < 0 can be
    /// (insideBox) for the narrow phase's culling. Never written to a file.
    std::shared_ptr<const ExactDistance> exact;
};

/// @a grid's values, states, background, transform and metadata as bricks (see
/// LevelSetBricks.h for the bound on the values). @a grid is not changed: free it after.
std::shared_ptr<const LevelSetBricks> toLevelSetGrid(const openvdb::FloatGrid& grid);

/// A standard FloatGrid of @a grid's decoded values (for files and OpenVDB's tools).
openvdb::FloatGrid::Ptr toFloatGrid(const LevelSetBricks& grid);

/// Initialise OpenVDB once per process (idempotent, thread-safe).
void initializeOpenVdb();

/// The box (in the asset frame) of the voxels of @a levelSet with φ < 0, widened by one voxel:
/// a trilinear sample can only be negative inside it. An empty box (min > max) if no voxel is
/// negative.
void insideBox(const LevelSetGrid& levelSet, Vec3& min, Vec3& max);

/// An upper bound on the slope |∇φ| of the trilinear interpolant of @a levelSet wherever
/// φ ≥ 0: the largest, over the cells with a corner at φ ≥ 0 (every point at φ ≥ 0 lies in
/// one), of the root of the sum of the squares of the cell's largest difference along each
/// axis, over the voxel size (in a cell each partial derivative is a mean of its four edges'
/// differences along its axis). So a point at φ = g > 0 cannot reach φ < 0 by a move shorter
/// than g over this: on the way φ stays ≥ 0 until it first crosses zero. About 1 for a signed
/// distance; the interior (where a mesh's fill or a shape's ridges may be steeper) does not
/// count.
double levelSetSlopeBound(const LevelSetGrid& levelSet);

struct GrainAsset;

/// What the narrow phase derives from @a asset's nodes and level set, never stored in its file:
/// the node blocks, the inside box (insideBox) and the slope bound (levelSetSlopeBound). Called
/// once an asset is baked or loaded.
void deriveContactBounds(GrainAsset& asset);

/// @a asset with its level set answering with @a distance (an analytic shape's exact distance,
/// AnalyticShape::exactDistance) instead of its voxels, and its contact bounds derived again
/// (the voxels still bound where φ < 0 can be, for culling). For references that must depend
/// on neither the voxel size nor how the voxels are stored.
GrainAsset withExactDistance(GrainAsset asset, std::shared_ptr<const ExactDistance> distance);

/// A linear transform with the given voxel size whose index (0,0,0) sits at @a origin.
openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin);

} // namespace lsdem
