/// @file TriangleMesh.h
/// @brief A plain indexed triangle mesh: the common currency between mesh files, analytic
///        shapes, remeshing, mass properties and surface nodes.
#pragma once

#include "lsdem/core/Vec3.h"

#include <array>
#include <vector>

namespace lsdem {

struct TriangleMesh
{
    std::vector<Vec3> vertices;                 ///< positions, in the user's length unit
    std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside

    bool empty() const { return vertices.empty() || triangles.empty(); }
};

/// Area of triangle t of @a mesh.
double triangleArea(const TriangleMesh& mesh, int t);

/// Sum of all triangle areas.
double surfaceArea(const TriangleMesh& mesh);

/// Apply x -> rotation * x + translation to every vertex.
void transformMesh(TriangleMesh& mesh, const Mat3& rotation, const Vec3& translation);

/// Axis-aligned bounds of the vertices: {min, max}.
std::array<Vec3, 2> meshBounds(const TriangleMesh& mesh);

} // namespace lsdem
