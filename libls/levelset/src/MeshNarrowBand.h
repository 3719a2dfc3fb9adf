/// @file MeshNarrowBand.h
/// @brief The narrow band of a mesh's level set (private to lsdem_levelset): each voxel near
///        the surface with its nearest triangle and its side, as ClosestTriangleCodes.h codes
///        them, in a ClosestTriangleGrid.h grid.
#pragma once

#include "lsdem/core/Vec3.h"
#include "lsdem/mesh/TriangleMesh.h"

#include <memory>

namespace lsdem::closest {
class CodeGrid;
}

namespace lsdem {

/// Every voxel (centre origin + voxelSize·index) within @a exteriorBandVoxels voxels outside
/// @a mesh's surface or within two inside it, active, coded with the triangle nearest to it
/// (the lowest-numbered of equally near ones) and its side (the pseudo-normals,
/// MeshPseudoNormals.h): exact distances, in double. Other voxels are inactive (their code
/// kOutside): the caller fills the inside. The grid's table covers every voxel within the
/// band's reach of a triangle's box. Deterministic on any thread
/// count. @a mesh: closed, manifold, consistently oriented (else lsdem::Error), with fewer
/// than closest::kMaxTriangles triangles.
std::unique_ptr<closest::CodeGrid> meshNarrowBand(const TriangleMesh& mesh, const Vec3& origin,
                                                   double voxelSize, int exteriorBandVoxels);

} // namespace lsdem
