/// @file MassProperties.h
/// @brief Volume, centroid and inertia of a solid bounded by a closed triangle mesh (exact for
///        the polyhedron, by the divergence theorem), and its principal frame.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

namespace lsdem {

/// Mass properties for unit density: mass equals volume.
struct MassProperties
{
    double volume = 0.0;                  ///< length^3
    Vec3 centroid = Vec3::Zero();         ///< length
    Mat3 inertia = Mat3::Zero();          ///< about the centroid, length^5 (times density)
};

/// Exact mass properties of the polyhedron bounded by @a mesh (closed, outward oriented).
MassProperties computeMassProperties(const TriangleMesh& mesh);

/// A rigid map from the input frame to a grain's principal frame: x_p = rotation*(x - centroid).
struct PrincipalFrame
{
    Mat3 rotation = Mat3::Identity();     ///< rows are the principal axes in input coordinates
    Vec3 centroid = Vec3::Zero();         ///< centroid in input coordinates
    Vec3 moments = Vec3::Zero();          ///< principal moments, ascending
};

/// The principal frame of @a props: axes sorted by ascending moment, right-handed. Each axis's
/// sign is fixed by @a mesh (the third moment of surface area along the axis is made
/// non-negative) so that a rotated copy of the same mesh maps to the same principal frame.
PrincipalFrame principalFrame(const MassProperties& props, const TriangleMesh& mesh);

} // namespace lsdem
