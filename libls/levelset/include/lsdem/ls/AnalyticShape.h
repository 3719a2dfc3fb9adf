/// @file AnalyticShape.h
/// @brief Primitive grain shapes with exact signed distance, normals, area and mass properties:
///        sphere (radius), box (full edge lengths), ellipsoid (semi-axes). Each is centred at
///        the origin and already in its principal frame.
#pragma once

#include "lsdem/ls/ExactDistance.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/mesh/TriangleMesh.h"

#include <memory>
#include <string>

namespace lsdem {

struct AnalyticShape
{
    enum class Kind { Sphere, Box, Ellipsoid };
    Kind kind = Kind::Sphere;
    Vec3 size = Vec3::Ones();  ///< sphere: (R,R,R); box: full edges (A,B,C); ellipsoid: semi-axes

    static AnalyticShape sphere(double radius);
    static AnalyticShape box(double a, double b, double c);
    static AnalyticShape ellipsoid(double a, double b, double c);

    /// Signed distance to the surface, negative inside (exact for all three kinds).
    double signedDistance(const Vec3& p) const;
    /// Closest point on the surface to @a p.
    Vec3 closestSurfacePoint(const Vec3& p) const;
    /// Outward unit normal at a surface point (for a box edge/corner: the mean of the faces').
    Vec3 outwardNormal(const Vec3& surfacePoint) const;
    /// The signed distance and its gradient as an ExactDistance, for a level set baked from
    /// this shape to be sampled exactly (LevelSetGrid::exact).
    std::shared_ptr<const ExactDistance> exactDistance() const;

    /// Exact surface area (the ellipsoid's by numerical quadrature to ~1e-12 relative).
    double surfaceArea() const;
    /// Exact mass properties for unit density (centroid at the origin, diagonal inertia).
    MassProperties massProperties() const;
    /// Half-extents of the axis-aligned bounding box.
    Vec3 halfExtents() const;

    /// A closed triangle mesh of the surface with edges about @a edgeLength long, vertices on
    /// the exact surface (box: a structured grid on each face; sphere/ellipsoid: a subdivided
    /// icosahedron projected onto the surface).
    TriangleMesh surfaceMesh(double edgeLength) const;

    /// "sphere R=5", "box 1x2x3", ... for provenance and summaries.
    std::string describe() const;
};

} // namespace lsdem
