/// @file LevelSetBricks.h
/// @brief A grain's level set as held in memory: 4³-voxel bricks of 8-bit codes on a plane
///        (16-bit beside creases, 24-bit values where no plane fits closely enough, 16-bit deep
///        inside the grain) under one dense table of the grid's bounding box. Built from a float grid
///        (toLevelSetGrid), turned back into one for files and OpenVDB's tools (toFloatGrid);
///        never modified.
///
/// Why: a sphere-like grain of radius 20 voxels in OpenVDB's 8³ float leaves takes ~415 KiB;
/// here ~115 KiB. Smaller bricks cover the surface shell more tightly, 1 or 2 bytes hold most
/// values, and the table replaces the tree walk (one multiply-add finds a brick).
///
/// Three kinds of brick, each value decoding to an exact float:
///
/// - **Wide** (3 bytes a value): q · step, q a signed 24-bit integer, step a power of two per
///   brick: 2^(c−22) where 2^c is the brick's largest |value| rounded up to a power of two, so
///   |q| ≤ 2^22. The stored value differs from the float it came from by less than 2^-21 of
///   the brick's largest |value| (half a step when rounded to nearest; a full step only where
///   that would lose the sign: a negative value never decodes to 0 or more, a positive one
///   never to 0 or less). Near the surface (|φ| ≤ 3√3 voxels in a brick that it crosses) that
///   is under 2.5e-6 voxel. Every other kind is decided on these "24-bit values".
/// - **Plane** (1 byte a value, 2 beside creases): the 24-bit values rounded
///   again, to the nearest multiple of a power of two at least their step (never across
///   zero), n · step with n = base + g·(i, j, k) + q: an integer plane over the brick's voxels
///   (i, j, k) and q an unsigned remainder. The distance to a surface is nearly linear over 4
///   voxels, so the remainders are small. The step is the least that fits (found by doubling
///   it). A value is within half a step of its 24-bit value (a whole one if it lies within
///   half a step of zero: it keeps its sign). Flat faces (a plane exactly) keep their 24-bit
///   values; creases and corners, where no plane fits, stay wide. Values at the background (a
///   bake caps the distance there, at the band's edge) bend the plane: the plane is fitted to
///   the others, and plane bricks decode to at most the background. Two widths:
///   - *8-bit* q ("narrow"), step at most the power of two in (2^-10, 2^-9] voxel
///     (kNarrowPlaneStepVoxels): a value is within 2^-10 + 2^-21·|largest| voxel of the float,
///     under 9.8e-4 voxel near the surface (2.0e-3 within 2^-10 voxel of it). Trilinear
///     interpolation of a curved surface already errs by more, by a ratio the remainders fix:
///     values that stray from their plane by S voxels over a brick are those of a curvature
///     that interpolation misses by about S/9 (exactly, for a quadratic), and 255 codes round
///     them to within S/255 at worst, under 1/28 of that (on a sphere of r voxels S is 2.25/r
///     to 4/r). That reasoning fails where the values stray from a plane at a crease while the
///     surface itself is flat (a block's face near its edge): interpolation is exact on the
///     face, so rounding would be the only error there. So 8 bits are used only where the
///     values are smooth (their least-squares quadratic fits them to within a quarter of their
///     spread about the plane: a sphere of 5 or more voxels, not a polyhedron's edge at a
///     sharp angle) and move no value near the surface (within √3 voxels: the corners a node
///     on it reads) by more than those values already stray from their own least-squares
///     plane. A rule of thumb, checked on tilted boxes (docs/assets.md), not a bound: a
///     shallow crease passes it.
///   - *16-bit* q otherwise, step at most kPlaneStepVoxels (2^-17 voxel): within 2^-18 +
///     2^-21·|largest| voxel of the float, under 6.3e-6 voxel near the surface.
/// - **Deep** (2 bytes a value): a brick whose every value lies kDeepVoxels or more below the
///   surface (as 24 bits would hold it) holds them as (base + q) · deepStep(), base one
///   integer per brick, q an unsigned 16-bit integer, deepStep() one power of two for the grid
///   in (2^-13, 2^-12] voxel, rounded down from its 24-bit value (so a deep value stays deep).
///   Such a value is less than deepStep() below its 24-bit value: under 2.5e-4 voxel in all.
///   No point within kDeepVoxels − √3 voxels of the surface reads one (a cell's corners lie
///   within √3 voxels of its points). Deeper, trilinear interpolation of a curved surface's
///   distance already errs by more (1/(4r) voxel for a sphere of r voxels: 10 to 60 times
///   more for spheres of 100 to 20 voxels); where φ is linear (a box's interior) the rounding
///   is the only error. Interior bricks are most of a finely resolved grain's bricks.
///
/// Encoding decoded values again gives the same values and bricks, so a saved and loaded asset
/// samples to the same bits as the one saved: a brick becomes a plane brick only if its
/// decoded values would be encoded again as the same plane brick (else it stays wide).
#pragma once

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace lsdem {

class LevelSetBricks
{
public:
    static constexpr int kLog2Dim = 2;
    static constexpr int kDim = 1 << kLog2Dim;                 ///< voxels along a brick edge
    static constexpr int kVoxels = kDim * kDim * kDim;         ///< voxels in a brick
    static constexpr int kMaskWords = (kVoxels + 63) / 64;     ///< 64-bit active-state words

    struct RawBrick;
    class Source;

    /// The values and active states of every voxel of @a grid (tiles included), its
    /// background, transform and metadata. Throws lsdem::Error if a value is not finite.
    explicit LevelSetBricks(const openvdb::FloatGrid& grid);

    /// The values and active states @a source gives, with @a header's background, transform
    /// and metadata (its tree is not read): for values made as they are read, without a
    /// float grid of them all. The source is used up (it may free what it holds as it goes).
    LevelSetBricks(const openvdb::FloatGrid& header, Source&& source);

    /// A standard FloatGrid of the decoded values, with the same active states, background,
    /// transform and metadata as the grid this was built from (for files and OpenVDB's tools).
    openvdb::FloatGrid::Ptr toFloatGrid() const;

    /// The value at index @a c, as decoded (background outside the bricks).
    float value(const openvdb::Coord& c) const { return decode(brickAt(c), offset(c - mOrigin)); }
    bool isValueOn(const openvdb::Coord& c) const { return isOn(brickAt(c), offset(c - mOrigin)); }
    /// The brick holding index @a c (the background brick outside the table).
    uint32_t brickAt(const openvdb::Coord& c) const
    {
        const openvdb::Coord l = c - mOrigin;
        return brick(l.x() >> kLog2Dim, l.y() >> kLog2Dim, l.z() >> kLog2Dim);
    }

    float background() const { return decode(kBackgroundBrick, 0); }
    /// Bound on |stored − original| of a value, relative to the largest |value| of its brick
    /// (wide bricks; the 24-bit values every kind starts from).
    static constexpr double kRelativeError = 1.0 / (1 << 21);
    /// The coarsest step of a 16-bit plane brick, in voxels: its values are within half of it
    /// (a whole one where the sign would be lost) of their 24-bit values.
    static constexpr double kPlaneStepVoxels = 1.0 / (1 << 17);
    /// The same for an 8-bit (narrow) plane brick: its step is at most the power of two in
    /// (1/2, 1] of this many voxels.
    static constexpr double kNarrowPlaneStepVoxels = 1.0 / (1 << 9);
    /// How far below the surface, in voxels, every value of a brick must lie for the brick to
    /// be stored deep (16 bits a value).
    static constexpr double kDeepVoxels = 3.0;
    /// The step of the deep bricks' values (a power of two in (2^-13, 2^-12] voxel; 0 when
    /// the grid's voxels are not cubes, and then no brick is deep): a deep value is at most
    /// this much below the float it came from, never above it.
    float deepStep() const { return mDeepStep; }
    /// Bricks stored: shared ones once, deep ones included.
    size_t brickCount() const { return mBrickStep.size(); }
    /// Bricks stored deep.
    size_t deepBrickCount() const { return mPlaneFirst - mWideBricks; }
    /// Bricks stored on a plane, narrow ones included.
    size_t planeBrickCount() const { return mBrickStep.size() - mPlaneFirst; }
    /// Bricks stored on a plane with 8-bit remainders.
    size_t narrowBrickCount() const { return mBrickStep.size() - mNarrowFirst; }

    openvdb::Index64 activeVoxelCount() const;
    openvdb::CoordBBox evalActiveVoxelBoundingBox() const;
    /// Bytes held (this object and its arrays).
    size_t memUsage() const;

    /// Calls @a visit(coord, value, active) for every voxel of a brick of the table that holds
    /// varying values, and @a visitUniform(bbox, value, active) for each brick of one value
    /// and state other than the inactive background.
    template <typename VisitVoxel, typename VisitUniform>
    void forEachBrick(VisitVoxel&& visit, VisitUniform&& visitUniform) const;

    // ---- for the sampler: "local" coordinates are index coordinates minus origin() ----
    /// The index of the first voxel of the table's first brick: the lowest corner of the
    /// voxels that are active or differ from the background (so bricks waste no more than
    /// 3 voxels per axis beyond them, whatever their alignment).
    const openvdb::Coord& origin() const { return mOrigin; }
    /// The voxels the table covers (empty if it holds no brick): everywhere else the value is
    /// the background.
    openvdb::CoordBBox tableBox() const
    {
        if (!mBricks[0] || !mBricks[1] || !mBricks[2]) return openvdb::CoordBBox();
        return openvdb::CoordBBox(mOrigin, mOrigin.offsetBy(int(mBricks[0]) * kDim - 1,
                                                            int(mBricks[1]) * kDim - 1,
                                                            int(mBricks[2]) * kDim - 1));
    }
    /// The brick at local brick coordinates (bx, by, bz); the background brick outside the
    /// table. Bricks of one value and state (the background, interior tiles) are stored once
    /// and shared, so every place has a brick and reading one never branches on its kind.
    uint32_t brick(int bx, int by, int bz) const
    {
        const auto ux = static_cast<uint32_t>(bx), uy = static_cast<uint32_t>(by),
                   uz = static_cast<uint32_t>(bz);
        if (ux >= mBricks[0] || uy >= mBricks[1] || uz >= mBricks[2]) return kBackgroundBrick;
        return mTable[(size_t(ux) * mBricks[1] + uy) * mBricks[2] + uz] & kIndexMask;
    }
    /// Offset of the voxel at local coordinates @a c within its brick: x-major.
    static int offset(const openvdb::Coord& c)
    {
        constexpr int m = kDim - 1;
        return ((c.x() & m) << (2 * kLog2Dim)) | ((c.y() & m) << kLog2Dim) | (c.z() & m);
    }
    /// The voxel at @a offset within a brick (the inverse of offset()).
    static openvdb::Coord voxelOf(int offset)
    {
        return openvdb::Coord(offset >> (2 * kLog2Dim), (offset >> kLog2Dim) & (kDim - 1),
                              offset & (kDim - 1));
    }
    /// g·(i, j, k) for the voxel (i, j, k) at @a offset: a plane brick's integer plane there.
    static int32_t planeAt(const int32_t* g, int offset)
    {
        const openvdb::Coord v = voxelOf(offset);
        return g[0] * v.x() + g[1] * v.y() + g[2] * v.z();
    }
    /// Whether brick @a brick is deep.
    bool isDeep(uint32_t brick) const { return brick >= mWideBricks && brick < mPlaneFirst; }
    /// Whether brick @a brick is a plane brick (narrow or not).
    bool isPlane(uint32_t brick) const { return brick >= mPlaneFirst; }
    /// Whether brick @a brick is a narrow plane brick (1 byte a value).
    bool isNarrow(uint32_t brick) const { return brick >= mNarrowFirst; }
    /// Whether brick @a brick holds 24-bit codes (3 bytes a value; narrow ones 1, the others 2).
    bool isWide(uint32_t brick) const { return brick < mWideBricks; }
    /// The value of voxel @a offset of brick @a brick.
    float decode(uint32_t brick, int offset) const
    {
        if (isWide(brick)) return decode(codes(brick) + 3 * offset, mBrickStep[brick]);
        int32_t n = mBase[brick - mWideBricks];
        if (isNarrow(brick)) {
            n += codes(brick)[offset];
        } else {
            uint16_t q = 0;
            std::memcpy(&q, codes(brick) + 2 * offset, sizeof q);
            n += q;
        }
        if (isPlane(brick)) n += planeAt(gradient(brick), offset);
        // exact: |n| ≤ 2^22 (checked when the brick was made), the step a power of two; voxels
        // at a band's edge decode to its cap (a deep brick's values are far below it)
        return std::min(static_cast<float>(n) * mBrickStep[brick], mPlaneCeiling);
    }
    /// A plane or deep brick's base code (the integer its voxel (0, 0, 0) adds its q to).
    int32_t base(uint32_t brick) const { return mBase[brick - mWideBricks]; }
    /// What a plane or deep brick's values are capped at: the grid's background.
    float planeCeiling() const { return mPlaneCeiling; }
    /// A plane brick's integer gradient (codes per voxel along x, y, z).
    const int32_t* gradient(uint32_t brick) const
    {
        return mGradient.data() + 3 * size_t(brick - mPlaneFirst);
    }
    /// The value whose 3-byte code (little-endian, two's complement) starts at @a code, which
    /// must lie in codes(): it is read as 4 bytes, one load instead of three (the array keeps
    /// a byte of padding after its last 24-bit code, or the first deep brick follows), and
    /// the fourth byte is shifted out.
    static float decode(const uint8_t* code, float step)
    {
        static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
                      "LevelSetBricks reads its 3-byte codes as little-endian words");
        uint32_t bits = 0;
        std::memcpy(&bits, code, sizeof bits);
        const int32_t q = static_cast<int32_t>(bits << 8) >> 8;  // sign-extend 24 bits
        return static_cast<float>(q) * step;  // exact: |q| ≤ 2^22, step a power of two (or q = 1)
    }
    /// Brick @a brick's codes: kVoxels of them, 3 bytes each (1 for narrow plane bricks, 2
    /// for the others). The wide bricks come first and the narrow ones last, so brick b starts
    /// at 64·(2b + min(b, W) − max(b, N) + N), W wide bricks and N the first narrow one.
    const uint8_t* codes(uint32_t brick) const
    {
        return mCode.data() + kVoxels * (2 * size_t(brick) + std::min(brick, mWideBricks) -
                                         std::max(brick, mNarrowFirst) + mNarrowFirst);
    }
    /// The step of brick @a brick's codes (deepStep() for a deep brick).
    float step(uint32_t brick) const { return mBrickStep[brick]; }

    /// One brick's voxels as a float grid holds them (while building).
    struct RawBrick
    {
        float value[kVoxels];
        uint64_t active[kMaskWords];
    };

    /// Where the builder reads the voxels, a brick at a time: a float grid's, or values made
    /// as they are read. Read twice, in parallel: once to choose each brick's kind, then once
    /// to write it, in order of x a few slabs at a time (releaseBelow after each).
    class Source
    {
    public:
        virtual ~Source() = default;
        /// The box holding every voxel that is active or whose value is not the background.
        virtual openvdb::CoordBBox valueBox() const = 0;
        /// Reads for one thread.
        class Reader
        {
        public:
            virtual ~Reader() = default;
            /// Every value and active state of the brick whose first voxel is @a origin.
            virtual void read(const openvdb::Coord& origin, RawBrick& raw) = 0;
        };
        virtual std::unique_ptr<Reader> reader() const = 0;
        /// Called during the second read, between readers, once no brick below x index @a x
        /// (exclusive) will be read again: a source may free what it holds there.
        virtual void releaseBelow(int x) { (void)x; }
    };

private:
    static constexpr uint32_t kBackgroundBrick = 0;
    static constexpr uint32_t kShared = 0x80000000u;  ///< table flag: a brick of one value
    static constexpr uint32_t kIndexMask = ~kShared;

    static_assert(kMaskWords == 1, "a brick's active states are one 64-bit mask");
    /// Brick @a brick's active states, one bit a voxel.
    uint64_t activeMask(uint32_t brick) const
    {
        return mMasks[mMaskOf.empty() ? mMaskOfMany[brick] : mMaskOf[brick]];
    }
    bool isOn(uint32_t brick, int offset) const { return ((activeMask(brick) >> offset) & 1u) != 0; }
    /// Each brick's active states as the distinct masks and an index a brick, from mActive
    /// (then freed): a grain's bricks hold few distinct masks (all on, all off, and those at
    /// the band's edge: 356 in the R/20 sphere's 919 bricks).
    void shareMasks();
    /// Calls @a visit(slot, origin, varies, raw) for each place of the table, read from
    /// @a source; places in parallel (rows of constant x and y), so @a visit must only write
    /// what belongs to its slot.
    template <typename Visit>
    void forEachRawBrick(const Source& source, Visit&& visit) const;
    /// The same for the places in slabs [@a firstSlab, @a endSlab) of constant x.
    template <typename Visit>
    void forEachRawBrick(const Source& source, uint32_t firstSlab, uint32_t endSlab,
                         Visit&& visit) const;
    /// The first voxel of the table's place @a slot.
    openvdb::Coord placeOrigin(size_t slot) const;

    // The constructor's passes, in their order (LevelSetBricks.cpp).
    struct Place;  ///< what pass 1 finds at a place of the table
    /// (value bits, active) of a brick of one value → that brick.
    using SharedBricks = std::map<std::pair<uint32_t, uint8_t>, uint32_t>;
    void chooseSteps(const openvdb::Vec3d& voxel);
    void sizeTable(const openvdb::CoordBBox& box);
    std::vector<Place> classifyPlaces(const Source& source) const;
    uint32_t layOutBricks(const std::vector<Place>& places, SharedBricks& shared);
    void allocateBricks(uint32_t bricks);
    void writeVaryingBricks(Source& source);
    uint8_t* writableCodes(uint32_t brick)
    {
        return mCode.data() + (codes(brick) - mCode.data());
    }
    /// Brick @a brick (already allocated) holding one value and state.
    void writeUniformBrick(uint32_t brick, float value, bool active);
    /// Brick @a brick (already allocated) holding @a raw's values, encoded, and states.
    void writeVaryingBrick(uint32_t brick, const RawBrick& raw);
    /// The same for a deep brick (@a raw passes deepCodes).
    void writeDeepBrick(uint32_t brick, const RawBrick& raw);
    /// A plane brick's encoding: its values are (base + g·(i, j, k) + q[k]) · step.
    struct PlaneCodes
    {
        bool narrow = false;  ///< q in 8 bits
        double step = 0.0;
        int32_t base = 0;
        int32_t gradient[3] = {0, 0, 0};
        uint16_t q[kVoxels] = {};
        bool operator==(const PlaneCodes& o) const
        {
            return narrow == o.narrow && step == o.step && base == o.base && std::equal(gradient, gradient + 3, o.gradient) &&
                   std::equal(q, q + kVoxels, o.q);
        }
    };
    /// Whether @a raw's values can be stored on a plane of the width @a narrow says (see the
    /// file's comment), and then their codes; it does not check that they would be encoded
    /// again the same (isPlaneBrick).
    bool planeCodes(const RawBrick& raw, bool narrow, PlaneCodes& out) const;
    /// The plane codes of @a raw: 8-bit ones if they fit and keep the surface's flat parts
    /// (keepsFlatSurface), else 16-bit ones if those fit; false if neither does.
    bool shellCodes(const RawBrick& raw, PlaneCodes& out) const;
    /// Whether @a codes move no value of @a raw near the surface (within √3 voxels) by more
    /// than those values stray from their least-squares plane.
    bool keepsFlatSurface(const RawBrick& raw, const PlaneCodes& codes) const;
    /// Whether @a raw (not deep) is stored as a plane brick, and then its codes: it has plane
    /// codes, and its decoded values are neither deep nor encoded as other plane codes.
    bool isPlaneBrick(const RawBrick& raw, PlaneCodes& codes) const;
    /// Brick @a brick (already allocated, a plane brick) holding @a raw's values.
    void writePlaneBrick(uint32_t brick, const RawBrick& raw);
    /// Whether @a raw's values can be stored deep, and then their codes in deep steps (before
    /// the base is taken off): each value, rounded to 24 bits as a brick of the other kind
    /// would hold it, kDeepVoxels or more below the surface and above −2^22 deep steps, and
    /// all within 65535 deep steps of each other.
    bool deepCodes(const RawBrick& raw, int32_t code[kVoxels]) const;

    openvdb::Coord mOrigin{0, 0, 0};  ///< index of the table's first voxel
    uint32_t mBricks[3] = {0, 0, 0};
    std::vector<uint32_t> mTable;        ///< per brick of the box, x-major: index | kShared
    /// An allocator that leaves new elements unwritten: pass 2 writes every code, so the
    /// storage's pages become resident as the bricks are written (a source freeing what it
    /// holds meanwhile), not all at once.
    template <typename T>
    struct UnwrittenAllocator : std::allocator<T>
    {
        template <typename U>
        struct rebind
        {
            using other = UnwrittenAllocator<U>;
        };
        UnwrittenAllocator() = default;
        template <typename U>
        UnwrittenAllocator(const UnwrittenAllocator<U>&) noexcept {}
        template <typename U>
        void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
        template <typename U, typename... Args>
        void construct(U* p, Args&&... args)
        {
            ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
        }
    };
    /// 3 bytes per voxel, kVoxels per brick (2 for deep bricks, after the others); 1 padding
    /// byte
    std::vector<uint8_t, UnwrittenAllocator<uint8_t>> mCode;
    std::vector<float> mBrickStep;       ///< per brick: a power of two, or the shared value
    uint32_t mWideBricks = 0;            ///< bricks [0, mWideBricks) are wide
    uint32_t mPlaneFirst = 0;            ///< then deep bricks up to this one, then plane ones
    uint32_t mNarrowFirst = 0;           ///< the 16-bit plane bricks up to this one, then narrow
    std::vector<int32_t> mBase;          ///< per deep or plane brick: its base code
    std::vector<int32_t> mGradient;      ///< per plane brick: 3 codes per voxel
    /// The grid's background: plane bricks decode to no more than it (a band's edge caps the
    /// distance there); infinite for a background ≤ 0, and then no brick is a plane brick.
    float mPlaneCeiling = 0.0f;
    double mPlaneStepLimit = 0.0;        ///< kPlaneStepVoxels voxels (0: no plane bricks)
    double mNarrowStepLimit = 0.0;       ///< a power of two: chooseSteps
    double mVoxel = 0.0;                 ///< the voxel's edge (cubic voxels; else 0)
    float mDeepStep = 0.0f;
    float mDeepBelow = 0.0f;             ///< −kDeepVoxels voxels: a deep brick's values are ≤
    std::vector<uint64_t> mActive;       ///< per brick, while building (shareMasks)
    std::vector<uint64_t> mMasks;        ///< the distinct active-state masks
    std::vector<uint16_t> mMaskOf;       ///< per brick: its mask in mMasks (up to 65536 masks)
    std::vector<uint32_t> mMaskOfMany;   ///< the same where there are more (mMaskOf empty)
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
                const uint32_t b = e & kIndexMask;
                const openvdb::Coord origin =
                    mOrigin.offsetBy(int(ix) * kDim, int(iy) * kDim, int(iz) * kDim);
                if (e & kShared) {
                    if (b != kBackgroundBrick)
                        visitUniform(openvdb::CoordBBox::createCube(origin, kDim), decode(b, 0),
                                     isOn(b, 0));
                    continue;
                }
                for (int n = 0; n < kVoxels; ++n) {
                    const openvdb::Coord c = origin + voxelOf(n);
                    visit(c, decode(b, n), isOn(b, n));
                }
            }
}

} // namespace lsdem
