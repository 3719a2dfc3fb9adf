/// @file NodeShape.h
/// @brief The surface around each node: its outward normal, a tangent, the curvature of the
///        surface there (the shape operator in that tangent frame) and the node's patch, its
///        Voronoi cell among its neighbours in its tangent plane. A contact that integrates the
///        traction over each node's patch (PatchQuadrature.h) reads the patch from here,
///        instead of treating the node as a point.
#pragma once

#include "lsdem/core/Vec3.h"

#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace lsdem {

struct GrainAsset;

/// The rays from a node along which its patch is described (and integrated): at angles
/// (k + ½)·2π/kPatchRays from t₁ toward t₂.
constexpr int kPatchRays = 16;

/// The angle of ray @a k.
double patchRayAngle(int k);

/// The surface near one node, in the asset frame: points x(u) = x + u₁t₁ + u₂t₂ − ½(uᵀSu)·m,
/// with t₂ = m × t₁ and S = [[k11, k12], [k12, k22]] (positive where the surface bends away
/// from its outward normal m, as a convex grain's does: a sphere of radius R has S = I/R).
/// Its patch reaches extents[k] along ray k.
struct NodeShape
{
    Vec3 normal = Vec3::UnitZ();   ///< m, unit, outward
    Vec3 tangent = Vec3::UnitX();  ///< t₁, unit, ⊥ m
    double k11 = 0.0, k12 = 0.0, k22 = 0.0;  ///< the shape operator, 1/length
    std::array<float, kPatchRays> extents{};  ///< the patch along each ray, length
    float reach = 0.0f;                        ///< the largest extent
    /// How far the patch bends toward a body it faces beyond its extents: ½·reach²·(the
    /// surface's concavity here, 0 where convex). A node farther than reach + lift from a
    /// plane (at a unit slope) cannot touch it.
    float lift = 0.0f;

    Vec3 secondTangent() const { return normal.cross(tangent); }
};

/// The shape at every node of @a asset. From the nodes themselves, which lie on the surface: a
/// jet w = a·u₁ + b·u₂ − ½uᵀSu fitted through the node to its 12 nearest neighbours on the same
/// sheet (first normals within 40°), the normal turned by (a, b) and the jet fitted again; good
/// to O((ρ/R)²) for neighbours out to ρ (0.3 % in curvature for a 4000-node ball). Where fewer
/// than 7 neighbours qualify (an edge, a corner, a lone node), and for an asset that carries its
/// exact distance (references), from its level set instead: m the unit gradient of φ at the
/// node, S the tangential part of φ's Hessian by central differences of ∇φ one voxel apart
/// (exact for an exact distance; from voxels each curvature errs by O(1/R), which is why the
/// nodes are preferred); a node where ∇φ vanishes gets a flat patch facing away from the
/// centroid. From the nodes too: each patch is the node's Voronoi cell in its tangent plane
/// among the nodes near it on the same side (normals less than 90° apart, so a thin plate's far
/// face does not cut it), at most twice the radius of the disk of the node's area; its extents
/// are scaled so that the rays' rule gives the cell's exact area. The cells tile the surface,
/// so a cell's area (not the node's tributary area) weighs its node.
std::vector<NodeShape> nodeShapesOf(const GrainAsset& asset);

/// How far beyond its node, toward a body it faces, a node's patch can reach: its largest
/// extent plus its lift, the largest over the nodes. A node farther than this (plus the body's
/// own bend) from a body cannot touch it.
double patchReachOf(const std::vector<NodeShape>& shapes);

/// The surface's largest concavity at the nodes, max(0, −λ_min(S)) over them, 1/length: how
/// much another body's patch facing this surface can find it bending toward it (0 for a convex
/// surface), which tells how far from it such a patch may touch it.
double concavityOf(const std::vector<NodeShape>& shapes);

/// A copy of @a asset with its node shapes, patch reach and concavity (GrainAsset::nodeShapes).
GrainAsset withNodeShapes(const GrainAsset& asset);

} // namespace lsdem
