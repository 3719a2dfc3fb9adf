/// @file MeshIO.h
/// @brief Read triangle meshes (OBJ, STL, PLY and whatever else assimp knows) and write OBJ,
///        STL (ASCII) and PLY (ASCII) files.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <string>

namespace lsdem {

/// Read all triangles of all meshes in @a path into one mesh, merging vertices that share a
/// position (STL files repeat them per triangle). Polygons are triangulated. Coordinates come
/// back at single precision (Debian's assimp reads floats): about 6e-8 relative.
/// @throw Error if the file is missing, unreadable, of unknown format, or holds no triangles.
TriangleMesh readMesh(const std::string& path);

/// Write @a mesh to @a path; the format follows the extension (.obj, .stl, .ply).
/// The file is written to a temporary and renamed, so a failure leaves nothing behind.
/// @throw Error on an unknown extension or a write failure.
void writeMesh(const TriangleMesh& mesh, const std::string& path);

} // namespace lsdem
