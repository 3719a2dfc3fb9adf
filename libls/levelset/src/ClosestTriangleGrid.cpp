#include "ClosestTriangleGrid.h"

#include <algorithm>

namespace lsdem::closest {

CodeLeaf::CodeLeaf(const openvdb::Coord& origin) : mOrigin(origin), mNarrow(kSize, 0) {}

CodeLeaf::CodeLeaf(const openvdb::Coord& origin, const std::array<openvdb::Int32, kSize>& codes,
                   const std::array<bool, kSize>& active)
    : mOrigin(origin)
{
    // The palette sorted, so each voxel's index is found by bisection (a band leaf holds a
    // few dozen to a few hundred distinct codes).
    for (int n = 0; n < kSize; ++n)
        if (active[size_t(n)]) mPalette.push_back(codes[size_t(n)]);
    std::sort(mPalette.begin(), mPalette.end());
    mPalette.erase(std::unique(mPalette.begin(), mPalette.end()), mPalette.end());
    mPalette.shrink_to_fit();
    if (mPalette.size() > 256)
        mWide.resize(kSize, 0);
    else
        mNarrow.resize(kSize, 0);
    for (int n = 0; n < kSize; ++n) {
        if (!active[size_t(n)]) continue;
        const auto at = std::lower_bound(mPalette.begin(), mPalette.end(), codes[size_t(n)]);
        store(n, uint16_t(at - mPalette.begin()));
    }
}

void CodeLeaf::store(int n, uint16_t index)
{
    if (mWide.empty())
        mNarrow[size_t(n)] = uint8_t(index);
    else
        mWide[size_t(n)] = index;
    mActive[size_t(n) >> 6] |= uint64_t(1) << (n & 63);
}

uint16_t CodeLeaf::paletteIndex(openvdb::Int32 code)
{
    // From the end: the fill sets a leaf's voxels layer by layer, most often to codes it has
    // just added.
    for (size_t i = mPalette.size(); i-- > 0;)
        if (mPalette[i] == code) return uint16_t(i);
    mPalette.push_back(code);
    if (mPalette.size() == 257) {  // the 257th code needs a wider index
        mWide.assign(mNarrow.begin(), mNarrow.end());
        std::vector<uint8_t>().swap(mNarrow);
    }
    return uint16_t(mPalette.size() - 1);
}

void CodeLeaf::set(int n, openvdb::Int32 code) { store(n, paletteIndex(code)); }

CodeGrid::CodeGrid(const openvdb::Coord& lowLeaf, const std::array<size_t, 3>& counts)
    : mLow(lowLeaf), mCounts(counts), mLeaves(counts[0] * counts[1] * counts[2])
{
}

void CodeGrid::set(const openvdb::Coord& c, openvdb::Int32 code)
{
    const size_t slot = slotOf(c);
    std::unique_ptr<CodeLeaf>& leaf = mLeaves.at(slot);  // (beyond the table: an error)
    if (!leaf) {
        constexpr int kMask = ~(CodeLeaf::kDim - 1);
        leaf = std::make_unique<CodeLeaf>(openvdb::Coord(c.x() & kMask, c.y() & kMask,
                                                         c.z() & kMask));
    }
    leaf->set(CodeLeaf::offset(c), code);
}

void CodeGrid::adopt(size_t slot, std::unique_ptr<CodeLeaf> leaf) { mLeaves.at(slot) = std::move(leaf); }

size_t CodeGrid::releaseBelow(int x)
{
    const size_t slab = mCounts[1] * mCounts[2];
    size_t freed = 0;
    for (; mReleasedSlabs < mCounts[0] &&
           (mLow.x() + int(mReleasedSlabs) + 1) * CodeLeaf::kDim <= x;
         ++mReleasedSlabs)
        for (size_t s = mReleasedSlabs * slab; s < (mReleasedSlabs + 1) * slab; ++s)
            if (mLeaves[s]) {
                mLeaves[s].reset();
                ++freed;
            }
    return freed;
}

openvdb::CoordBBox CodeGrid::activeBox() const
{
    openvdb::CoordBBox box;  // empty
    for (const auto& leaf : mLeaves)
        if (leaf) leaf->forEachOn([&](int n, openvdb::Int32) {
            box.expand(leaf->origin() + CodeLeaf::localCoord(n));
        });
    return box;
}

} // namespace lsdem::closest
