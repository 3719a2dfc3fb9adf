/// @file ClosestTriangleCodes.h
/// @brief How a mesh's level set is held while it is baked (private to lsdem_levelset): one
///        32-bit code a voxel, its closest triangle and what is known of its side, held in a
///        ClosestTriangleGrid.h grid. The distances are made from these codes only as the
///        bricks are written.
#pragma once

#include <openvdb/openvdb.h>

#include <cstddef>
#include <limits>

namespace lsdem::closest {

/// An inactive voxel: outside the band and not reached by the interior fill (what the grid
/// reads for it).
constexpr openvdb::Int32 kOutside = std::numeric_limits<openvdb::Int32>::max();
/// Set on a band voxel's code: its distance is the exact one to its nearest triangle, on the
/// side the sign bit says. Codes without it are the fill's, inside.
constexpr openvdb::Int32 kBandBit = openvdb::Int32(1) << 30;
/// The sign bit: set on an inside band voxel's code. Alone, no triangle.
constexpr openvdb::Int32 kInsideBit = std::numeric_limits<openvdb::Int32>::min();
constexpr openvdb::Int32 kNoTriangle = kInsideBit;
constexpr openvdb::Int32 kTriangleMask = kBandBit - 1;
/// Triangles are numbered below this (kOutside's triangle bits are not a triangle).
constexpr std::size_t kMaxTriangles = std::size_t(1) << 29;

/// A band voxel's code: its nearest triangle @a t, on the side @a outside says.
inline openvdb::Int32 bandCode(openvdb::Int32 t, bool outside)
{
    return outside ? (t | kBandBit) : (t | kBandBit | kInsideBit);
}
/// Whether @a code names a triangle (a band voxel, or one the fill has reached).
inline bool holdsTriangle(openvdb::Int32 code) { return code != kNoTriangle && code != kOutside; }
inline openvdb::Int32 triangleOf(openvdb::Int32 code) { return code & kTriangleMask; }
/// Whether a voxel whose code holds a triangle lies outside the mesh.
inline bool isOutside(openvdb::Int32 code) { return (code & kBandBit) && code >= 0; }

} // namespace lsdem::closest
