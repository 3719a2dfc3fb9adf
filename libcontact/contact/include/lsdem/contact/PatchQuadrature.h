/// @file PatchQuadrature.h
/// @brief Each node as the patch it stands for, not a point. The adapted law's force is the
///        integral of the traction kn*·d over the surface, and a node at a point samples d
///        there: where a contact is narrower than the nodes' spacing (a ball rolling on a
///        floor under its own weight), the grain then rolls over its nodes like a polyhedron
///        over its vertices. Patch quadrature takes each node's patch, its Voronoi cell in its
///        tangent plane bent as the surface bends there (NodeShape.h), takes the other body's
///        depth over it to second order, and integrates the positive part: exactly along each
///        ray from the node, by a periodic trapezoid rule over the rays' angles. A node wholly
///        inside gives k·(its patch's area)·(mean depth over it), one wholly outside nothing,
///        and one at the contact's edge the part of its patch that is in.
#pragma once

#include "lsdem/contact/NodeContact.h"
#include "lsdem/ls/NodeShape.h"

#include <string>
#include <vector>

namespace lsdem {

/// How a contact law samples the traction over a grain's surface.
enum class NodeQuadrature {
    Point,  ///< at each node (the paper's rule): d of the node times its area
    Patch,  ///< over each node's patch (PatchQuadrature.h)
};

/// "node" or "patch".
std::string nodeQuadratureName(NodeQuadrature q);
/// Inverse of nodeQuadratureName. @throw Error naming the accepted values.
NodeQuadrature parseNodeQuadrature(const std::string& name);

/// The other body's depth over a node's patch to second order in the offset u = (u₁, u₂)
/// along the node's tangents t₁, t₂: d(u) = d0 + g·u − ½·uᵀCu.
struct PatchDepth
{
    double d0 = 0.0;
    double g1 = 0.0, g2 = 0.0;
    double c11 = 0.0, c12 = 0.0, c22 = 0.0;
};

/// Integrals over the disk |u| ≤ ρ of the positive part d⁺ of a PatchDepth.
struct PatchIntegral
{
    double area = 0.0;         ///< ∫[d > 0] dA, length²
    double depth = 0.0;        ///< ∫d⁺ dA, length³
    double squareDepth = 0.0;  ///< ∫(d⁺)² dA, length⁴
    double moment1 = 0.0, moment2 = 0.0;  ///< ∫d⁺·u dA, length⁴
    /// The deepest d⁺ along the rays (each ray's own maximum, at an end or its vertex): the
    /// patch's deepest point when it lies on a ray, a little less between them, length.
    double peak = 0.0;
};

/// The integrals of @a d⁺ over the disk of radius @a radius, along kPatchRays rays
/// (NodeShape.h); the trapezoid rule over them is exact for a disk wholly in contact (its
/// integrands are trigonometric polynomials of degree ≤ 4 in the angle), which is done in
/// closed form.
PatchIntegral integratePatch(const PatchDepth& d, double radius);

/// The integrals of @a d⁺ over a node's patch, which reaches @a extents[k] along ray k and
/// @a reach at most (NodeShape::extents, NodeShape::reach).
PatchIntegral integratePatch(const PatchDepth& d, const std::array<float, kPatchRays>& extents,
                             double reach);

/// An upper bound on d over the disk of radius @a radius: no part of the patch is in contact
/// when it is ≤ 0.
double patchPeakBound(const PatchDepth& d, double radius);

/// The radius of the disk of area @a area.
double patchRadius(double area);

/// A node's shape in some frame (the frame of the other body's φ): outward normal m, tangents
/// t₁, t₂ = m × t₁ and the shape operator S in them (NodeShape.h).
struct PatchFrame
{
    Vec3 normal, tangent1, tangent2;
    double k11 = 0.0, k12 = 0.0, k22 = 0.0;
};

/// The frame of a node of shape @a shape (asset frame), turned by @a rotation into the frame
/// of the other body's φ.
PatchFrame patchFrame(const NodeShape& shape, const Eigen::Matrix3d& rotation);

/// The depth over the patch of a node facing a body whose signed distance φ at the node is
/// @a phi, with gradient @a gradient and Hessian along the node's tangents (@a h11, @a h12,
/// @a h22; zero for a plane), all in the frame of @a frame: d0 = −φ, g = −(∇φ·t₁, ∇φ·t₂),
/// C = −(∇φ·m)·S + H (the patch bends away from the body as the node's surface bends, and the
/// body's surface bends away from the patch as its own does).
PatchDepth patchDepth(const PatchFrame& frame, double phi, const Vec3& gradient, double h11,
                      double h12, double h22);

/// The contact of node @a node (shape @a shape, its frame @a frame in the world) with a body
/// whose depth over its patch is @a depth and whose normal there is @a normal: appended to
/// @a out, at the patch's centre moved half its depth along the normal, if any of the patch
/// is in contact (and counted in @a inContact).
void addPatchContact(int node, const NodeShape& shape, const PatchFrame& frame,
                     const PatchDepth& depth, const Vec3& nodePosition, const Vec3& normal,
                     std::vector<NodeContact>& out, long long& inContact);

/// Fill the depth, area, mean square depth and peak of @a contact from @a integral (its node,
/// normal and point are the caller's), and return the offset of the force's centre (the
/// depth-weighted centroid of the patch) along @a frame's tangents. False, and @a contact
/// untouched, when no part of the patch is in contact.
bool fillPatchContact(const PatchIntegral& integral, const PatchFrame& frame,
                      NodeContact& contact, Vec3& offset);

} // namespace lsdem
