/// @file ClosestTriangleGrid.h
/// @brief Where a mesh's closest-triangle codes (ClosestTriangleCodes.h) are held while its
///        level set is baked (private to lsdem_levelset): 8³ leaves in a dense table over the
///        band's box; each leaf keeps the distinct codes it holds (its palette) and, per voxel,
///        an index into them.
///
/// The voxels of a leaf share a few nearest triangles (a few dozen by the surface, a handful
/// deep inside), so an index of one byte a voxel (two once a leaf holds more than 256 distinct
/// codes) stands for the four-byte code that an OpenVDB Int32 tree kept at every voxel of its
/// leaves. The codes are the bake's largest store, held whole from the interior fill's end
/// until the bricks are written (docs/assets.md, "Cost").
#pragma once

#include "ClosestTriangleCodes.h"

#include <openvdb/math/Coord.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace lsdem::closest {

/// An 8³ block of voxels: which are active, and each active one's code.
class CodeLeaf
{
public:
    static constexpr int kLog2Dim = 3;
    static constexpr int kDim = 1 << kLog2Dim;
    static constexpr int kSize = kDim * kDim * kDim;

    /// The leaf whose first voxel is @a origin (a multiple of kDim on each axis), none active.
    explicit CodeLeaf(const openvdb::Coord& origin);
    /// The leaf at @a origin whose voxels n with @a active[n] hold @a codes[n].
    CodeLeaf(const openvdb::Coord& origin, const std::array<openvdb::Int32, kSize>& codes,
             const std::array<bool, kSize>& active);

    /// A voxel's place in its leaf, x*64 + y*8 + z (as OpenVDB's leaves number them).
    static int offset(const openvdb::Coord& c)
    {
        constexpr int kMask = kDim - 1;
        return ((c.x() & kMask) << (2 * kLog2Dim)) | ((c.y() & kMask) << kLog2Dim) |
               (c.z() & kMask);
    }
    static openvdb::Coord localCoord(int n)
    {
        return {n >> (2 * kLog2Dim), (n >> kLog2Dim) & (kDim - 1), n & (kDim - 1)};
    }

    const openvdb::Coord& origin() const { return mOrigin; }
    bool isOn(int n) const { return ((mActive[size_t(n) >> 6] >> (n & 63)) & 1u) != 0; }
    /// Voxel @a n's code; kOutside if it is not active.
    openvdb::Int32 code(int n) const
    {
        if (!isOn(n)) return kOutside;
        return mPalette[mWide.empty() ? mNarrow[size_t(n)] : mWide[size_t(n)]];
    }
    /// Make voxel @a n active with @a code. Not thread-safe within a leaf (the palette grows).
    void set(int n, openvdb::Int32 code);
    /// f(n, code) for each active voxel, in increasing n.
    template <typename F>
    void forEachOn(F&& f) const
    {
        for (int w = 0; w < int(mActive.size()); ++w)
            for (uint64_t bits = mActive[size_t(w)]; bits != 0; bits &= bits - 1) {
                const int n = 64 * w + __builtin_ctzll(bits);
                f(n, code(n));
            }
    }

private:
    /// @a code's place in the palette, added if new (the indices widened to 16 bits when
    /// it outgrows 8).
    uint16_t paletteIndex(openvdb::Int32 code);
    /// Voxel @a n made active with the palette's code @a index.
    void store(int n, uint16_t index);

    openvdb::Coord mOrigin;
    std::array<uint64_t, kSize / 64> mActive{};
    std::vector<openvdb::Int32> mPalette;  ///< the distinct codes, in the order first set
    std::vector<uint8_t> mNarrow;          ///< per voxel, while the palette holds ≤ 256 codes
    std::vector<uint16_t> mWide;           ///< per voxel, once it holds more (mNarrow empty)
};

/// The leaves over a box of leaves, in a dense table (x-major); voxels outside it are never
/// active. Reading is thread-safe; changing the grid is not.
class CodeGrid
{
public:
    /// The table of @a counts leaves from the leaf whose first voxel is kDim·@a lowLeaf.
    CodeGrid(const openvdb::Coord& lowLeaf, const std::array<size_t, 3>& counts);

    size_t slotCount() const { return mLeaves.size(); }
    /// The leaf holding voxel @a c, or null (none made, or @a c beyond the table).
    const CodeLeaf* leaf(const openvdb::Coord& c) const
    {
        const size_t slot = slotOf(c);
        return slot == kNoSlot ? nullptr : mLeaves[slot].get();
    }
    const CodeLeaf* leafAtSlot(size_t slot) const { return mLeaves[slot].get(); }
    bool isOn(const openvdb::Coord& c) const
    {
        const CodeLeaf* l = leaf(c);
        return l && l->isOn(CodeLeaf::offset(c));
    }
    /// Voxel @a c's code; kOutside if it is not active.
    openvdb::Int32 code(const openvdb::Coord& c) const
    {
        const CodeLeaf* l = leaf(c);
        return l ? l->code(CodeLeaf::offset(c)) : kOutside;
    }

    /// Voxel @a c (within the table) made active with @a code; its leaf made if need be.
    void set(const openvdb::Coord& c, openvdb::Int32 code);
    /// @a leaf put at table slot @a slot (the slot of its origin).
    void adopt(size_t slot, std::unique_ptr<CodeLeaf> leaf);
    /// Every leaf whose voxels all lie below x = @a x freed (no voxel of them read again);
    /// how many there were.
    size_t releaseBelow(int x);

    /// The box of the active voxels (empty if there are none).
    openvdb::CoordBBox activeBox() const;

private:
    static constexpr size_t kNoSlot = ~size_t(0);
    size_t slotOf(const openvdb::Coord& c) const
    {
        size_t slot = 0;
        for (int a = 0; a < 3; ++a) {
            const int l = (c[a] >> CodeLeaf::kLog2Dim) - mLow[a];
            if (l < 0 || size_t(l) >= mCounts[size_t(a)]) return kNoSlot;
            slot = slot * mCounts[size_t(a)] + size_t(l);
        }
        return slot;
    }

    openvdb::Coord mLow;
    std::array<size_t, 3> mCounts;
    std::vector<std::unique_ptr<CodeLeaf>> mLeaves;
    size_t mReleasedSlabs = 0;  ///< the leading x-slabs of the table freed so far
};

} // namespace lsdem::closest
