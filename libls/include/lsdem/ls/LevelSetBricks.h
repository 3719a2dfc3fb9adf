/// @file LevelSetBricks.h
/// @brief A grain's level set as held in memory: 4³-voxel bricks of 24-bit values under one
///        dense table of the grid's bounding box. Built from a float grid (toLevelSetGrid),
///        turned back into one for files and OpenVDB's tools (toFloatGrid); never modified.
///
/// Why: a sphere-like grain of radius 20 voxels in OpenVDB's 8³ float leaves takes ~415 KiB;
/// here about half. Smaller bricks cover the surface shell more tightly, 3 bytes hold a value,
/// and the table replaces the tree walk (one multiply-add finds a brick).
///
/// Storage: a value is q · step, q a signed 24-bit integer, step a power of two per brick:
/// 2^(c−22) where 2^c is the brick's largest |value| rounded up to a power of two, so
/// |q| ≤ 2^22 and the decoded value is exact in float. The stored value differs from the float
/// it came from by less than 2^-21 of the brick's largest |value| (half a step when rounded to
/// nearest; a full step only where that would lose the sign: a negative value never decodes
/// to 0 or more, a positive one never to 0 or less). Near the surface (|φ| ≤ 3√3 voxels in a
/// brick that it crosses) that is under 2.5e-6 voxel. Encoding decoded values again gives the
/// same values, so a saved and loaded asset samples to the same bits as the one saved.
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <vector>

namespace lsdem {

class LevelSetBricks
{
public:
    static constexpr int kLog2Dim = 2;
    static constexpr int kDim = 1 << kLog2Dim;                 ///< voxels along a brick edge
    static constexpr int kVoxels = kDim * kDim * kDim;         ///< voxels in a brick
    static constexpr int kMaskWords = (kVoxels + 63) / 64;     ///< 64-bit active-state words

    /// The values and active states of every voxel of @a grid (tiles included), its
    /// background, transform and metadata. Throws lsdem::Error if a value is not finite.
    explicit LevelSetBricks(const openvdb::FloatGrid& grid);

    /// A standard FloatGrid of the decoded values, with the same active states, background,
    /// transform and metadata as the grid this was built from (for files and OpenVDB's tools).
    openvdb::FloatGrid::Ptr toFloatGrid() const;

    /// The value at index @a c, as decoded (background outside the bricks).
    float value(const openvdb::Coord& c) const
    {
        const uint32_t e = entry(c.x() >> kLog2Dim, c.y() >> kLog2Dim, c.z() >> kLog2Dim);
        return (e & kUniform) ? mUniformValue[e & ~kUniform] : decode(e, offset(c));
    }
    bool isValueOn(const openvdb::Coord& c) const;

    float background() const { return mUniformValue[0]; }
    /// Bound on |stored − original| of a value, relative to the largest |value| of its brick.
    static constexpr double kRelativeError = 1.0 / (1 << 21);

    openvdb::Index64 activeVoxelCount() const;
    openvdb::CoordBBox evalActiveVoxelBoundingBox() const;
    /// Bytes held (this object and its arrays).
    size_t memUsage() const;

    /// Calls @a visit(coord, value, active) for every voxel of a brick (not the empty ones),
    /// and @a visitUniform(bbox, value, active) for each brick of one value and state.
    template <typename VisitVoxel, typename VisitUniform>
    void forEachBrick(VisitVoxel&& visit, VisitUniform&& visitUniform) const;

    // ---- for the sampler: a brick's entry in the table, and its decoded values ----
    static constexpr uint32_t kUniform = 0x80000000u;  ///< entry flag: one value, index below
    /// The entry of the brick with brick coordinates (bx, by, bz): a brick index, or kUniform
    /// with an index into the uniform values (0: the background, outside the table too).
    uint32_t entry(int bx, int by, int bz) const
    {
        const auto ux = static_cast<uint32_t>(bx - mBrickMin[0]);
        const auto uy = static_cast<uint32_t>(by - mBrickMin[1]);
        const auto uz = static_cast<uint32_t>(bz - mBrickMin[2]);
        if (ux >= mBricks[0] || uy >= mBricks[1] || uz >= mBricks[2]) return kUniform;
        return mTable[(size_t(ux) * mBricks[1] + uy) * mBricks[2] + uz];
    }
    float uniformValue(uint32_t e) const { return mUniformValue[e & ~kUniform]; }
    /// Offset of voxel @a c within its brick: x-major, as in OpenVDB's leaves.
    static int offset(const openvdb::Coord& c)
    {
        constexpr int m = kDim - 1;
        return ((c.x() & m) << (2 * kLog2Dim)) | ((c.y() & m) << kLog2Dim) | (c.z() & m);
    }
    /// The value of voxel @a offset of dense brick @a brick.
    float decode(uint32_t brick, int offset) const
    {
        return decode(codes(brick) + 3 * offset, mBrickStep[brick]);
    }
    /// The value whose 3-byte code (little-endian, two's complement) starts at @a code.
    static float decode(const uint8_t* code, float step)
    {
        const uint32_t bits = uint32_t(code[0]) | uint32_t(code[1]) << 8 | uint32_t(code[2]) << 16;
        const int32_t q = static_cast<int32_t>(bits << 8) >> 8;  // sign-extend 24 bits
        return static_cast<float>(q) * step;  // both exact: |q| ≤ 2^22, step a power of two
    }
    const uint8_t* codes(uint32_t brick) const { return mCode.data() + size_t(brick) * 3 * kVoxels; }
    float step(uint32_t brick) const { return mBrickStep[brick]; }

    /// One brick's voxels as a float grid holds them (while building).
    struct RawBrick
    {
        float value[kVoxels];
        uint64_t active[kMaskWords];
    };

private:
    /// Calls @a visit(slot, origin, varies, raw) for each brick of the table, read from a grid.
    template <typename Visit>
    void forEachRawBrick(openvdb::FloatGrid::ConstAccessor& accessor, Visit&& visit) const;
    /// Encode @a raw as dense brick @a brick.
    void encode(uint32_t brick, const RawBrick& raw);

    int mBrickMin[3] = {0, 0, 0};  ///< brick coordinates of the table's first brick
    uint32_t mBricks[3] = {0, 0, 0};
    std::vector<uint32_t> mTable;        ///< per brick of the box, x-major
    std::vector<uint8_t> mCode;          ///< 3 bytes per voxel, kVoxels per dense brick
    std::vector<float> mBrickStep;       ///< per dense brick, a power of two
    std::vector<uint64_t> mActive;       ///< kMaskWords per dense brick
    std::vector<float> mUniformValue;    ///< [0]: the background (inactive)
    std::vector<uint8_t> mUniformActive;
    openvdb::math::Transform::Ptr mTransform;
    openvdb::MetaMap::Ptr mMetadata;
};

template <typename VisitVoxel, typename VisitUniform>
void LevelSetBricks::forEachBrick(VisitVoxel&& visit, VisitUniform&& visitUniform) const
{
    for (uint32_t ix = 0; ix < mBricks[0]; ++ix)
        for (uint32_t iy = 0; iy < mBricks[1]; ++iy)
            for (uint32_t iz = 0; iz < mBricks[2]; ++iz) {
                const uint32_t e = mTable[(size_t(ix) * mBricks[1] + iy) * mBricks[2] + iz];
                const openvdb::Coord origin((mBrickMin[0] + int(ix)) * kDim,
                                            (mBrickMin[1] + int(iy)) * kDim,
                                            (mBrickMin[2] + int(iz)) * kDim);
                if (e & kUniform) {
                    if (e != kUniform)
                        visitUniform(openvdb::CoordBBox::createCube(origin, kDim),
                                     mUniformValue[e & ~kUniform], mUniformActive[e & ~kUniform] != 0);
                    continue;
                }
                const uint64_t* mask = mActive.data() + size_t(e) * kMaskWords;
                for (int n = 0; n < kVoxels; ++n) {
                    const openvdb::Coord c = origin.offsetBy(n >> (2 * kLog2Dim),
                                                             (n >> kLog2Dim) & (kDim - 1),
                                                             n & (kDim - 1));
                    visit(c, decode(e, n), ((mask[n >> 6] >> (n & 63)) & 1u) != 0);
                }
            }
}

} // namespace lsdem
