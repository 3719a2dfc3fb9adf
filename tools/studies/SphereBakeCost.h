/// @file SphereBakeCost.h
/// @brief What baking one of the studies' analytic spheres costs on this machine, for the
///        estimates the sphere studies and the verification suite print before they start.
#pragma once

namespace lsdem {

/// Seconds of wall time (2 cores of this machine) to bake an analytic sphere of radius
/// @a radius at voxel @a voxel with about @a nodes nodes: the level set's voxels (the filled
/// ball and its band) plus the remeshed surface's nodes. Measured, not derived: see
/// docs/cube27.md#cost (the fit and its check).
double sphereBakeSeconds(double radius, double voxel, int nodes);

} // namespace lsdem
