/// @file NodeShape.h
/// @brief The surface around each node to second order: its outward normal, a tangent, and the
///        curvature of the surface there (the shape operator in that tangent frame). A contact
///        that integrates the traction over each node's patch (PatchQuadrature.h) reads the
///        patch's shape from here, instead of treating the node as a point.
#pragma once

#include "lsdem/core/Vec3.h"

#include <Eigen/Geometry>

#include <vector>

namespace lsdem {

struct GrainAsset;

/// The surface near one node, in the asset frame: points x(u) = x + u₁t₁ + u₂t₂ − ½(uᵀSu)·m,
/// with t₂ = m × t₁ and S = [[k11, k12], [k12, k22]] (positive where the surface bends away
/// from its outward normal m, as a convex grain's does: a sphere of radius R has S = I/R).
struct NodeShape
{
    Vec3 normal = Vec3::UnitZ();   ///< m, unit, outward
    Vec3 tangent = Vec3::UnitX();  ///< t₁, unit, ⊥ m
    double k11 = 0.0, k12 = 0.0, k22 = 0.0;  ///< the shape operator, 1/length

    Vec3 secondTangent() const { return normal.cross(tangent); }
};

/// The shape at every node of @a asset, from its level set: m the unit gradient of φ at the
/// node, S the tangential part of φ's Hessian (for a signed distance, the shape operator),
/// the Hessian by central differences of ∇φ one voxel apart (exact where the asset carries
/// its exact distance). A node where ∇φ vanishes gets a flat patch facing away from the
/// centroid.
std::vector<NodeShape> nodeShapesOf(const GrainAsset& asset);

/// How far beyond its node, toward a body it faces, a node's patch can reach: over the disk
/// of the node's area, |u| + ½|u|²·(the surface's concavity there), the largest over the nodes.
/// A node farther than this (plus the body's own bend) from a body cannot touch it.
double patchReachOf(const GrainAsset& asset, const std::vector<NodeShape>& shapes);

/// A copy of @a asset with its node shapes and patch reach (GrainAsset::nodeShapes).
GrainAsset withNodeShapes(const GrainAsset& asset);

} // namespace lsdem
