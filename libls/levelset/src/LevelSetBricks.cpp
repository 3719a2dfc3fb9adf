#include "lsdem/ls/LevelSetBricks.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace lsdem {

namespace {

uint32_t floatBits(float v)
{
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof(bits));
    return bits;
}

/// Whether @a raw holds more than one value or state; if not, its value and state are left
/// in [0] alone (the active mask then 1 or 0).
bool variesWithin(LevelSetBricks::RawBrick& raw)
{
    for (int k = 1; k < LevelSetBricks::kVoxels; ++k)
        if (raw.value[k] != raw.value[0]) return true;
    const bool on = (raw.active[0] & 1u) != 0;
    for (int k = 0; k < LevelSetBricks::kVoxels; ++k)
        if ((((raw.active[k >> 6] >> (k & 63)) & 1u) != 0) != on) return true;
    raw.active[0] = on ? 1u : 0u;
    return false;
}

/// A float grid's voxels, read voxel by voxel (the accessor keeps the last leaf).
class FloatGridReader : public LevelSetBricks::Source::Reader
{
public:
    explicit FloatGridReader(const openvdb::FloatGrid& grid) : mAccessor(grid.getConstAccessor()) {}

    void read(const openvdb::Coord& origin, LevelSetBricks::RawBrick& raw) override
    {
        using Leaf = openvdb::FloatTree::LeafNodeType;
        constexpr int kDim = LevelSetBricks::kDim;
        std::memset(raw.active, 0, sizeof(raw.active));
        for (int x = 0; x < kDim; ++x)
            for (int y = 0; y < kDim; ++y)
                for (int z = 0; z < kDim; ++z) {
                    const openvdb::Coord c = origin.offsetBy(x, y, z);
                    const int k = LevelSetBricks::offset(openvdb::Coord(x, y, z));
                    bool on = false;
                    if (const Leaf* leaf = mAccessor.probeConstLeaf(c)) {
                        const openvdb::Index n = Leaf::coordToOffset(c);
                        raw.value[k] = leaf->getValue(n);
                        on = leaf->isValueOn(n);
                    } else {
                        raw.value[k] = mAccessor.getValue(c);
                        on = mAccessor.isValueOn(c);
                    }
                    if (on) raw.active[k >> 6] |= uint64_t(1) << (k & 63);
                }
    }

private:
    openvdb::FloatGrid::ConstAccessor mAccessor;
};

/// The box of index space holding every voxel of @a grid that is active or differs from the
/// background: such voxels of its leaves, and such tiles.
openvdb::CoordBBox gridValueBox(const openvdb::FloatGrid& grid)
{
    const float background = grid.background();
    openvdb::CoordBBox box;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf)
        for (auto it = leaf->cbeginValueAll(); it; ++it)
            if (it.isValueOn() || *it != background) box.expand(it.getCoord());
    auto it = grid.tree().cbeginValueAll();
    it.setMaxDepth(openvdb::FloatTree::RootNodeType::LEVEL - 1);  // tiles only, no voxels
    for (; it; ++it)
        if (it.isValueOn() || *it != background) box.expand(it.getBoundingBox());
    return box;
}

/// A float grid's voxels, tiles included.
class FloatGridSource : public LevelSetBricks::Source
{
public:
    explicit FloatGridSource(const openvdb::FloatGrid& grid) : mGrid(grid) {}
    openvdb::CoordBBox valueBox() const override { return gridValueBox(mGrid); }
    std::unique_ptr<Reader> reader() const override
    {
        return std::make_unique<FloatGridReader>(mGrid);
    }

private:
    const openvdb::FloatGrid& mGrid;
};

} // namespace

// The constructor's passes share the table under construction, so they are members; each
// reads what the one before it left: the deep and plane steps, the table's size, pass 1
// classifying the places, the bricks laid out in place order, the storage, then pass 2
// writing the bricks.
LevelSetBricks::LevelSetBricks(const openvdb::FloatGrid& grid)
    : LevelSetBricks(grid, FloatGridSource(grid))
{
}

LevelSetBricks::LevelSetBricks(const openvdb::FloatGrid& header, Source&& source)
    : mPlaneCeiling(header.background() > 0.0f ? header.background()
                                                : std::numeric_limits<float>::infinity()),
      mTransform(header.transform().copy()),
      mMetadata(header.copyMeta())
{
    chooseSteps(header.voxelSize());
    sizeTable(source.valueBox());
    SharedBricks shared;
    shared[{floatBits(header.background()), 0}] = kBackgroundBrick;
    // (The places, a temporary, are freed before the storage is made.)
    const uint32_t bricks = layOutBricks(classifyPlaces(source), shared);
    allocateBricks(bricks);
    for (const auto& [uniform, brick] : shared) {
        float value = 0.0f;
        std::memcpy(&value, &uniform.first, sizeof value);
        writeUniformBrick(brick, value, uniform.second != 0);
    }
    writeVaryingBricks(source);
    shareMasks();
}

void LevelSetBricks::shareMasks()
{
    std::map<uint64_t, uint32_t> index;
    std::vector<uint32_t> maskOf(mActive.size());
    for (size_t b = 0; b < mActive.size(); ++b) {
        const auto [it, added] = index.emplace(mActive[b], uint32_t(mMasks.size()));
        if (added) mMasks.push_back(mActive[b]);
        maskOf[b] = it->second;
    }
    if (mMasks.size() <= size_t(std::numeric_limits<uint16_t>::max()) + 1)
        mMaskOf.assign(maskOf.begin(), maskOf.end());
    else
        mMaskOfMany = std::move(maskOf);
    std::vector<uint64_t>().swap(mActive);
    mMasks.shrink_to_fit();
}

/// The deep bricks' step: the power of two in (2^-13, 2^-12] voxel; and the plane bricks'
/// coarsest, kPlaneStepVoxels voxels for 16 bits and the power of two in (2^-10, 2^-9] voxel
/// for 8 (cubic voxels only: else neither kind is used). The latter is a power of two
/// whatever the voxel, so 255 codes span at least 255·2^-10 voxel (a sphere of 9 voxels'
/// shell bricks).
void LevelSetBricks::chooseSteps(const openvdb::Vec3d& voxel)
{
    if (!(voxel[0] > 0.0 && voxel[0] == voxel[1] && voxel[1] == voxel[2])) return;
    // The power of two in (limit/2, limit] for a limit of kVoxels voxels.
    const auto octaveBelow = [&](double voxels) {
        int e = 0;
        std::frexp(voxels * voxel[0], &e);  // = m · 2^e, m in [0.5, 1)
        return std::ldexp(1.0, e - 1);
    };
    mVoxel = voxel[0];
    if (std::isfinite(mPlaneCeiling)) {
        mPlaneStepLimit = kPlaneStepVoxels * voxel[0];
        mNarrowStepLimit = octaveBelow(kNarrowPlaneStepVoxels);
    }
    mDeepStep = float(octaveBelow(std::ldexp(1.0, -12)));
    // The float at or below −kDeepVoxels voxels: a deep value is at least that deep.
    const double below = -kDeepVoxels * voxel[0];
    mDeepBelow = float(below);
    if (double(mDeepBelow) > below)
        mDeepBelow = std::nextafter(mDeepBelow, -std::numeric_limits<float>::infinity());
}

/// The table over @a box (the grid's values), every place the background brick to begin with.
void LevelSetBricks::sizeTable(const openvdb::CoordBBox& box)
{
    if (box.empty()) return;
    mOrigin = box.min();
    double places = 1.0;
    for (int k = 0; k < 3; ++k) {
        mBricks[k] = uint32_t((int64_t(box.max()[k]) - box.min()[k]) / kDim + 1);
        places *= mBricks[k];
    }
    // The table is dense: a grid whose values spread over a huge box (a fog volume's
    // tiles, say) would need more than its voxels are worth.
    if (places > double(1u << 28))
        throw Error("level set",
                    "the grid's values span " + std::to_string(box.dim().x()) + " x " +
                        std::to_string(box.dim().y()) + " x " +
                        std::to_string(box.dim().z()) +
                        " voxels, too large a box for lsdem's level-set table",
                    "lsdem samples grain-sized level sets; crop or rebuild the grid");
    mTable.assign(size_t(mBricks[0]) * mBricks[1] * mBricks[2], kShared | kBackgroundBrick);
}

/// Eight bytes a place (the table of a 100k-triangle grain's has 150k places, and this list
/// is held beside the source's values).
struct LevelSetBricks::Place
{
    bool varies : 1;
    bool deep : 1;
    bool plane : 1;
    bool narrow : 1;  ///< a plane brick of 8-bit remainders
    bool finite : 1;
    bool uniformActive : 1;  ///< a brick of one value: its voxels' state
    uint32_t uniformBits = 0;  ///< a brick of one value: the value's bits

    Place()
        : varies(false), deep(false), plane(false), narrow(false), finite(true),
          uniformActive(false)
    {
    }
    SharedBricks::key_type uniform() const { return {uniformBits, uint8_t(uniformActive)}; }
};

/// Pass 1, in parallel: what each place of the table holds (varying values, or one value and
/// state), and whether its values are all finite.
std::vector<LevelSetBricks::Place>
LevelSetBricks::classifyPlaces(const Source& source) const
{
    static_assert(sizeof(Place) == 8, "a place's classes and value in 8 bytes");
    std::vector<Place> places(mTable.size());
    forEachRawBrick(source, [&](size_t slot, const openvdb::Coord&, bool varies, const RawBrick& b) {
        Place& p = places[slot];
        p.varies = varies;
        int32_t unused[kVoxels];
        p.deep = varies && deepCodes(b, unused);
        PlaneCodes codes;
        p.plane = varies && !p.deep && isPlaneBrick(b, codes);
        p.narrow = p.plane && codes.narrow;
        for (int k = 0; k < (varies ? kVoxels : 1); ++k) p.finite &= std::isfinite(b.value[k]);
        if (!varies) {
            p.uniformBits = floatBits(b.value[0]);
            p.uniformActive = (b.active[0] & 1u) != 0;
        }
    });
    return places;
}

/// In place order, one thread: each place's brick into the table, and the bricks of one value
/// into @a shared (which holds the background's, brick 0); returns the number of bricks. Brick
/// 0 is the inactive background, shared by every such place and by all outside; the bricks of
/// varying values and each new value of one come next in the order of their first place, then
/// the deep bricks in the order of their places, then the 16-bit plane bricks and last the
/// narrow ones, likewise, so the layout does not depend on the thread count.
uint32_t LevelSetBricks::layOutBricks(const std::vector<Place>& places, SharedBricks& shared)
{
    uint32_t bricks = 1;
    for (size_t slot = 0; slot < places.size(); ++slot) {
        const Place& p = places[slot];
        if (!p.finite) {
            const openvdb::Coord origin = placeOrigin(slot);
            throw Error("level set",
                        "the grid holds a value that is not a finite number near index (" +
                            std::to_string(origin.x()) + ", " + std::to_string(origin.y()) +
                            ", " + std::to_string(origin.z()) + ")",
                        "rebuild the level set; lsdem samples finite distances only");
        }
        if (p.deep || p.plane) continue;
        if (p.varies) {
            mTable[slot] = bricks++;
            continue;
        }
        auto it = shared.find(p.uniform());
        if (it == shared.end()) it = shared.emplace(p.uniform(), bricks++).first;
        mTable[slot] = kShared | it->second;
    }
    mWideBricks = bricks;
    for (size_t slot = 0; slot < places.size(); ++slot)
        if (places[slot].deep) mTable[slot] = bricks++;
    mPlaneFirst = bricks;
    for (size_t slot = 0; slot < places.size(); ++slot)
        if (places[slot].plane && !places[slot].narrow) mTable[slot] = bricks++;
    mNarrowFirst = bricks;
    for (size_t slot = 0; slot < places.size(); ++slot)
        if (places[slot].narrow) mTable[slot] = bricks++;
    return bricks;
}

/// The storage of @a bricks bricks, sized once (grown by doubling it would hold up to twice
/// its size), plus the padding byte that decode() may read after the last 24-bit code when no
/// 16-bit brick follows.
void LevelSetBricks::allocateBricks(uint32_t bricks)
{
    const size_t twoBytes = mNarrowFirst - mWideBricks, oneByte = bricks - mNarrowFirst;
    mCode.resize((size_t(mWideBricks) * 3 + twoBytes * 2 + oneByte) * kVoxels + 1);
    mCode.back() = 0;  // the padding: every other byte is written with its brick
    mBrickStep.assign(bricks, 0.0f);
    mBase.assign(bricks - mWideBricks, 0);
    mGradient.assign(3 * size_t(bricks - mPlaneFirst), 0);
    mActive.assign(size_t(bricks) * kMaskWords, 0);
}

/// Pass 2, in parallel: the bricks of varying values, each into its own place; in order of x,
/// two slabs at a time, the source told after each what it will not be asked for again.
void LevelSetBricks::writeVaryingBricks(Source& source)
{
    auto write = [&](size_t slot, const openvdb::Coord&, bool varies, const RawBrick& b) {
        if (!varies) return;
        const uint32_t brick = mTable[slot] & kIndexMask;
        if (isDeep(brick))
            writeDeepBrick(brick, b);
        else if (isPlane(brick))
            writePlaneBrick(brick, b);
        else
            writeVaryingBrick(brick, b);
    };
    constexpr uint32_t kSlabsAtATime = 2;  // 8 voxels: an OpenVDB leaf's width
    for (uint32_t first = 0; first < mBricks[0]; first += kSlabsAtATime) {
        const uint32_t end = std::min(mBricks[0], first + kSlabsAtATime);
        forEachRawBrick(source, first, end, write);
        source.releaseBelow(mOrigin.x() + int(end) * kDim);
    }
}

openvdb::Coord LevelSetBricks::placeOrigin(size_t slot) const
{
    const size_t yz = size_t(mBricks[1]) * mBricks[2];
    const auto ix = int(slot / yz), iy = int((slot % yz) / mBricks[2]), iz = int(slot % mBricks[2]);
    return mOrigin.offsetBy(ix * kDim, iy * kDim, iz * kDim);
}

template <typename Visit>
void LevelSetBricks::forEachRawBrick(const Source& source, Visit&& visit) const
{
    forEachRawBrick(source, 0, mBricks[0], visit);
}

template <typename Visit>
void LevelSetBricks::forEachRawBrick(const Source& source, uint32_t firstSlab, uint32_t endSlab,
                                     Visit&& visit) const
{
    // Rows of constant x and y in parallel, each with its own reader; every place once.
    const size_t rows = size_t(endSlab - firstSlab) * mBricks[1];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rows, 8), [&](const tbb::blocked_range<size_t>& range) {
        const std::unique_ptr<Source::Reader> reader = source.reader();
        RawBrick raw;
        for (size_t row = range.begin(); row != range.end(); ++row) {
            const uint32_t ix = firstSlab + uint32_t(row / mBricks[1]);
            const auto iy = uint32_t(row % mBricks[1]);
            size_t slot = (size_t(ix) * mBricks[1] + iy) * mBricks[2];
            for (uint32_t iz = 0; iz < mBricks[2]; ++iz, ++slot) {
                const openvdb::Coord origin =
                    mOrigin.offsetBy(int(ix) * kDim, int(iy) * kDim, int(iz) * kDim);
                reader->read(origin, raw);
                visit(slot, origin, variesWithin(raw), raw);
            }
        }
    });
}

void LevelSetBricks::writeUniformBrick(uint32_t brick, float value, bool active)
{
    // One value v: q = 1 and step = v decode to v exactly.
    mBrickStep[brick] = value;
    uint8_t* code = writableCodes(brick);
    for (int k = 0; k < kVoxels; ++k) {
        code[3 * k] = 1;
        code[3 * k + 1] = code[3 * k + 2] = 0;
    }
    std::fill_n(mActive.begin() + std::ptrdiff_t(size_t(brick) * kMaskWords), kMaskWords,
                active ? ~uint64_t(0) : uint64_t(0));
}

namespace {

/// The step of a brick's 24-bit codes: 2^(c − 22) with 2^c ≥ its largest |value|, so every
/// |q| ≤ 2^22.
double wideStep(const LevelSetBricks::RawBrick& raw)
{
    float largest = 0.0f;
    for (float v : raw.value) largest = std::max(largest, std::abs(v));
    int c = 0;
    const double mantissa = std::frexp(double(largest), &c);  // largest = mantissa · 2^c
    if (mantissa == 0.5) --c;                                  // already a power of two
    return largest > 0.0f ? std::ldexp(1.0, c - 22) : 1.0;
}

/// The 24-bit code of @a v: to the nearest step, but never across zero (the sign decides
/// contact).
int32_t wideCode(double v, double step)
{
    auto q = static_cast<int32_t>(std::llround(v / step));
    if (v < 0.0 && q >= 0) q = -1;
    if (v > 0.0 && q <= 0) q = 1;
    return q;
}

/// The band's cap (a grid's background) @a ceiling as 24 bits of step @a wide hold it: a value
/// at or above it is at the cap. A ceiling beyond 2^22 steps lies above every value: infinity.
double wideCap(double ceiling, double wide)
{
    return ceiling <= std::ldexp(wide, 22) ? double(wideCode(ceiling, wide)) * wide
                                           : std::numeric_limits<double>::infinity();
}

/// A plane brick's remainders run from 0 to this (a narrow one's to 255).
constexpr int64_t kPlaneCodes = std::numeric_limits<uint16_t>::max();
constexpr int64_t kNarrowPlaneCodes = std::numeric_limits<uint8_t>::max();

/// Deep codes: below this in size a deep value is a multiple of the 24-bit step its brick
/// would have (so encoding it again gives it back), and converts to float exactly.
constexpr double kDeepCodeLimit = double(1 << 22);

} // namespace

void LevelSetBricks::writeVaryingBrick(uint32_t brick, const RawBrick& raw)
{
    const double step = wideStep(raw);
    mBrickStep[brick] = float(step);
    std::copy(raw.active, raw.active + kMaskWords,
              mActive.begin() + std::ptrdiff_t(size_t(brick) * kMaskWords));
    uint8_t* code = writableCodes(brick);
    for (int k = 0; k < kVoxels; ++k) {
        const auto bits = static_cast<uint32_t>(wideCode(raw.value[k], step));
        code[3 * k] = uint8_t(bits);
        code[3 * k + 1] = uint8_t(bits >> 8);
        code[3 * k + 2] = uint8_t(bits >> 16);
    }
}

bool LevelSetBricks::deepCodes(const RawBrick& raw, int32_t code[kVoxels]) const
{
    if (!(mDeepStep > 0.0f)) return false;
    for (float v : raw.value)
        if (!std::isfinite(v)) return false;  // refused by the constructor
    // Decided on the values as 24 bits would hold them, so the values a deep or other brick
    // decodes to are decided the same way when encoded again (a saved and loaded asset).
    const double step = wideStep(raw), deepBelow = mDeepBelow;
    for (int k = 0; k < kVoxels; ++k) {
        const double stored = double(wideCode(raw.value[k], step)) * step;
        if (!(stored <= deepBelow)) return false;
        // Rounded down, so the stored value stays at least as deep.
        const double deep = std::floor(stored / mDeepStep);
        if (!(deep > -kDeepCodeLimit)) return false;
        code[k] = static_cast<int32_t>(deep);
    }
    const auto [lowest, highest] = std::minmax_element(code, code + kVoxels);
    return *highest - *lowest <= int32_t(std::numeric_limits<uint16_t>::max());
}

void LevelSetBricks::writeDeepBrick(uint32_t brick, const RawBrick& raw)
{
    int32_t code[kVoxels];
    deepCodes(raw, code);  // true: the brick was numbered deep for it
    const int32_t base = *std::min_element(code, code + kVoxels);
    mBase[brick - mWideBricks] = base;
    mBrickStep[brick] = mDeepStep;
    std::copy(raw.active, raw.active + kMaskWords,
              mActive.begin() + std::ptrdiff_t(size_t(brick) * kMaskWords));
    uint8_t* out = writableCodes(brick);
    for (int k = 0; k < kVoxels; ++k) {
        const auto q = static_cast<uint16_t>(code[k] - base);
        std::memcpy(out + 2 * k, &q, sizeof q);
    }
}

bool LevelSetBricks::planeCodes(const RawBrick& raw, bool narrow, PlaneCodes& out) const
{
    const double stepLimit = narrow ? mNarrowStepLimit : mPlaneStepLimit;
    const int64_t largest = narrow ? kNarrowPlaneCodes : kPlaneCodes;
    if (!(stepLimit > 0.0)) return false;
    const double ceiling = mPlaneCeiling;
    for (float v : raw.value)
        if (!std::isfinite(v) || double(v) > ceiling) return false;
    // Values at the ceiling (a band's edge, where a bake caps the distance at the background)
    // bend the distance out of its plane: they only need codes that decode to the ceiling or
    // above (decode() takes the least of the two), so the plane is fitted to the others.
    // Which values are at the ceiling is decided on the 24-bit values, as every kind is.
    const double wide = wideStep(raw);
    const double cap = wideCap(ceiling, wide);
    double stored[kVoxels];
    bool capped[kVoxels];
    for (int k = 0; k < kVoxels; ++k) {
        stored[k] = double(wideCode(raw.value[k], wide)) * wide;
        capped[k] = stored[k] >= cap;
    }
    // Two planes are tried, in this order: the least-squares plane through the free voxels'
    // codes (if they span the brick's three directions), and the one through every voxel's,
    // the capped ones at the cap (a corner of a few free voxels at the band's edge). Over a
    // 4³ brick the normal equations of the second are diagonal about its centre: Σ(i − 3/2)² =
    // 80 in each direction.
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    for (int k = 0; k < kVoxels; ++k) {
        if (capped[k]) continue;
        const openvdb::Coord v = voxelOf(k);
        const Eigen::Vector4d x(1.0, v.x(), v.y(), v.z());
        normal += x * x.transpose();
    }
    const Eigen::LDLT<Eigen::Matrix4d> fit(normal);
    const bool spans = fit.info() == Eigen::Success && fit.isPositive() &&
                       fit.vectorD().minCoeff() > 1e-9 * fit.vectorD().maxCoeff();
    // The least spread of the codes about the planes that did not fit for their spread alone
    // (0 if one did not fit for a capped voxel): how far the step may jump.
    int64_t spread = std::numeric_limits<int64_t>::max();
    const auto fitsPlane = [&](const int32_t (&n)[kVoxels], const int32_t (&g)[3], double step,
                               int32_t (&rest)[kVoxels], int64_t& lowest) {
        lowest = std::numeric_limits<int64_t>::max();
        int64_t highest = std::numeric_limits<int64_t>::min();
        for (int k = 0; k < kVoxels; ++k) {
            rest[k] = n[k] - planeAt(g, k);
            if (capped[k]) continue;
            lowest = std::min<int64_t>(lowest, rest[k]);
            highest = std::max<int64_t>(highest, rest[k]);
        }
        if (lowest > highest) {  // every value capped: the plane's codes are free
            lowest = *std::min_element(rest, rest + kVoxels);
            highest = lowest;
        }
        if (highest - lowest > largest) {
            spread = std::min(spread, highest - lowest);
            return false;
        }
        // A capped voxel's code: the least that decodes to the ceiling or above. (With a
        // capped voxel the brick's largest |value| is at least the ceiling, so the ceiling is
        // at most 2^22 steps.)
        for (int k = 0; k < kVoxels; ++k) {
            if (!capped[k]) continue;
            const int64_t atCeiling = int64_t(std::ceil(ceiling / step));
            const int64_t q = std::max<int64_t>(atCeiling - (n[k] - rest[k]) - lowest, 0);
            if (q > largest) {
                spread = 0;
                return false;
            }
            rest[k] = static_cast<int32_t>(lowest + q);
        }
        return true;
    };
    // From the 24-bit values, each step from theirs up to the limit, the first whose codes lie
    // within the largest remainder (255 or 65535) of one of those planes, rounded. Codes that
    // spread over S about their plane spread over about S/2^j at 2^j times the step (the fit
    // is linear in the codes), so the steps at which they would still spread over more than
    // twice the largest are skipped.
    for (double step = wide; step <= stepLimit;) {
        int32_t n[kVoxels];
        Eigen::Vector4d freeMoment = Eigen::Vector4d::Zero();
        double allMoment[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < kVoxels; ++k) {
            n[k] = wideCode(stored[k], step);
            const openvdb::Coord v = voxelOf(k);
            if (!capped[k]) freeMoment += Eigen::Vector4d(1.0, v.x(), v.y(), v.z()) * double(n[k]);
            for (int a = 0; a < 3; ++a) allMoment[a] += (v[a] - 1.5) * n[k];
        }
        Eigen::Vector3d gradients[2];
        int candidates = 0;
        if (spans) gradients[candidates++] = fit.solve(freeMoment).tail<3>();
        gradients[candidates++] = Eigen::Vector3d(allMoment[0], allMoment[1], allMoment[2]) / 80.0;
        int32_t rest[kVoxels], g[3];
        int64_t lowest = 0;
        bool found = false;
        for (int c = 0; c < candidates && !found; ++c) {
            for (int a = 0; a < 3; ++a) {
                if (!(std::abs(gradients[c][a]) < double(1 << 24))) return false;
                g[a] = static_cast<int32_t>(std::llround(gradients[c][a]));
            }
            found = fitsPlane(n, g, step, rest, lowest);
        }
        if (!found) {
            int doublings = 1;
            while (doublings < 24 && spread > (largest << (doublings + 1))) ++doublings;
            step = std::ldexp(step, doublings);
            spread = std::numeric_limits<int64_t>::max();
            continue;
        }
        out.narrow = narrow;
        out.step = step;
        out.base = static_cast<int32_t>(lowest);
        std::copy(g, g + 3, out.gradient);
        for (int k = 0; k < kVoxels; ++k) out.q[k] = static_cast<uint16_t>(rest[k] - lowest);
        return true;
    }
    return false;
}

namespace {

/// Whether the 24-bit values @a stored of a brick (those @a free: not at the band's cap) are
/// smooth: within a quarter of their spread about their least-squares plane of their
/// least-squares quadratic. A curved surface's distance is (a sphere of 5 or more voxels: 0.21
/// of it at most, of 10 or more 0.08); a crease's is not (where a tilted box's edge passes
/// through bricks of its faces: 0.4 to 0.65).
bool isSmooth(const double (&stored)[LevelSetBricks::kVoxels],
              const bool (&free)[LevelSetBricks::kVoxels])
{
    using Basis = Eigen::Matrix<double, 10, 1>;
    const auto basis = [](int k) {
        const openvdb::Coord v = LevelSetBricks::voxelOf(k);
        const double x = v.x() - 1.5, y = v.y() - 1.5, z = v.z() - 1.5;
        Basis b;
        b << 1.0, x, y, z, x * x, y * y, z * z, x * y, y * z, x * z;
        return b;
    };
    Eigen::Matrix<double, 10, 10> normal = Eigen::Matrix<double, 10, 10>::Zero();
    Basis moment = Basis::Zero();
    Eigen::Matrix4d normal4 = Eigen::Matrix4d::Zero();
    Eigen::Vector4d moment4 = Eigen::Vector4d::Zero();
    for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
        if (!free[k]) continue;
        const Basis b = basis(k);
        normal += b * b.transpose();
        moment += b * stored[k];
        normal4 += b.head<4>() * b.head<4>().transpose();
        moment4 += b.head<4>() * stored[k];
    }
    const Eigen::LDLT<Eigen::Matrix<double, 10, 10>> quadratic(normal);
    const Eigen::LDLT<Eigen::Matrix4d> plane(normal4);
    const auto spans = [](const auto& fit) {
        return fit.info() == Eigen::Success && fit.isPositive() &&
               fit.vectorD().minCoeff() > 1e-9 * fit.vectorD().maxCoeff();
    };
    if (!spans(quadratic) || !spans(plane)) return false;
    const Basis q = quadratic.solve(moment);
    const Eigen::Vector4d p = plane.solve(moment4);
    double low = std::numeric_limits<double>::infinity(), high = -low, quadraticResidual = 0.0;
    for (int k = 0; k < LevelSetBricks::kVoxels; ++k) {
        if (!free[k]) continue;
        const Basis b = basis(k);
        const double aboutPlane = stored[k] - p.dot(b.head<4>());
        low = std::min(low, aboutPlane);
        high = std::max(high, aboutPlane);
        quadraticResidual = std::max(quadraticResidual, std::abs(stored[k] - q.dot(b)));
    }
    return quadraticResidual <= 0.25 * (high - low);
}

} // namespace

bool LevelSetBricks::keepsFlatSurface(const RawBrick& raw, const PlaneCodes& codes) const
{
    // The 24-bit values within √3 voxels of the surface, their plane and how far the codes move
    // them (all decided on the 24-bit values, as every kind is).
    const double wide = wideStep(raw), near = std::sqrt(3.0) * mVoxel;
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d moment = Eigen::Vector4d::Zero();
    double stored[kVoxels];
    bool isNear[kVoxels];
    double moved = 0.0;
    int count = 0;
    for (int k = 0; k < kVoxels; ++k) {
        stored[k] = double(wideCode(raw.value[k], wide)) * wide;
        isNear[k] = std::abs(stored[k]) <= near;
        if (!isNear[k]) continue;
        const openvdb::Coord v = voxelOf(k);
        const Eigen::Vector4d x(1.0, v.x(), v.y(), v.z());
        normal += x * x.transpose();
        moment += x * stored[k];
        const int32_t n = codes.base + int32_t(codes.q[k]) + planeAt(codes.gradient, k);
        moved = std::max(moved, std::abs(double(n) * codes.step - stored[k]));
        ++count;
    }
    if (count == 0 || moved == 0.0) return true;  // no surface here, or nothing moved
    // A crease (a polyhedron's edge) strays from a plane though the faces beside it are flat.
    // (The voxels at the band's cap, as planeCodes tells them, bend it too: they are left out.)
    const double cap = wideCap(mPlaneCeiling, wide);
    bool free[kVoxels];
    for (int k = 0; k < kVoxels; ++k) free[k] = stored[k] < cap;
    if (!isSmooth(stored, free)) return false;
    // A smooth brick whose near voxels are too few to fix a plane (the surface clips a corner)
    // strays from its plane as a whole: it is curved there.
    const Eigen::LDLT<Eigen::Matrix4d> fit(normal);
    if (count < 4 || fit.info() != Eigen::Success || !fit.isPositive() ||
        !(fit.vectorD().minCoeff() > 1e-9 * fit.vectorD().maxCoeff()))
        return true;
    const Eigen::Vector4d plane = fit.solve(moment);
    double stray = 0.0;
    for (int k = 0; k < kVoxels; ++k) {
        if (!isNear[k]) continue;
        const openvdb::Coord v = voxelOf(k);
        stray = std::max(stray, std::abs(stored[k] - plane.dot(Eigen::Vector4d(1.0, v.x(), v.y(), v.z()))));
    }
    return moved <= stray;
}

bool LevelSetBricks::shellCodes(const RawBrick& raw, PlaneCodes& out) const
{
    return (planeCodes(raw, true, out) && keepsFlatSurface(raw, out)) ||
           planeCodes(raw, false, out);
}

bool LevelSetBricks::isPlaneBrick(const RawBrick& raw, PlaneCodes& codes) const
{
    if (!shellCodes(raw, codes)) return false;
    // Its decoded values must come back as this brick: not deep, and the same plane codes.
    RawBrick decoded = raw;
    for (int k = 0; k < kVoxels; ++k) {
        const int32_t n = codes.base + int32_t(codes.q[k]) + planeAt(codes.gradient, k);
        decoded.value[k] = std::min(static_cast<float>(double(n) * codes.step), mPlaneCeiling);
    }
    int32_t unused[kVoxels];
    PlaneCodes again;
    return !deepCodes(decoded, unused) && shellCodes(decoded, again) && again == codes;
}

void LevelSetBricks::writePlaneBrick(uint32_t brick, const RawBrick& raw)
{
    PlaneCodes codes;
    shellCodes(raw, codes);  // true: the brick was numbered a plane brick of this width for it
    mBase[brick - mWideBricks] = codes.base;
    std::copy(codes.gradient, codes.gradient + 3,
              mGradient.begin() + std::ptrdiff_t(3 * size_t(brick - mPlaneFirst)));
    mBrickStep[brick] = float(codes.step);
    std::copy(raw.active, raw.active + kMaskWords,
              mActive.begin() + std::ptrdiff_t(size_t(brick) * kMaskWords));
    uint8_t* out = writableCodes(brick);
    if (codes.narrow)
        for (int k = 0; k < kVoxels; ++k) out[k] = static_cast<uint8_t>(codes.q[k]);
    else
        for (int k = 0; k < kVoxels; ++k) std::memcpy(out + 2 * k, &codes.q[k], sizeof codes.q[k]);
}

openvdb::FloatGrid::Ptr LevelSetBricks::toFloatGrid() const
{
    auto result = openvdb::FloatGrid::create(background());
    static_cast<openvdb::MetaMap&>(*result) = *mMetadata;
    result->setTransform(mTransform->copy());
    auto accessor = result->getAccessor();
    const float bg = background();
    forEachBrick(
        [&](const openvdb::Coord& c, float value, bool active) {
            if (active)
                accessor.setValueOn(c, value);
            else if (value != bg)
                accessor.setValueOff(c, value);
        },
        [&](const openvdb::CoordBBox& brick, float value, bool active) {
            result->tree().fill(brick, value, active);
        });
    return result;
}

openvdb::Index64 LevelSetBricks::activeVoxelCount() const
{
    std::vector<openvdb::Index64> perBrick(mBrickStep.size(), 0);
    for (size_t b = 0; b < perBrick.size(); ++b)
        perBrick[b] = std::bitset<64>(activeMask(uint32_t(b))).count();
    openvdb::Index64 count = 0;
    for (uint32_t e : mTable) count += perBrick[e & kIndexMask];
    return count;
}

openvdb::CoordBBox LevelSetBricks::evalActiveVoxelBoundingBox() const
{
    openvdb::CoordBBox box;
    forEachBrick(
        [&](const openvdb::Coord& c, float, bool active) {
            if (active) box.expand(c);
        },
        [&](const openvdb::CoordBBox& brick, float, bool active) {
            if (active) box.expand(brick);
        });
    return box;
}

size_t LevelSetBricks::memUsage() const
{
    return sizeof(*this) + mTable.capacity() * sizeof(uint32_t) +
           mCode.capacity() + mBrickStep.capacity() * sizeof(float) +
           mBase.capacity() * sizeof(int32_t) + mGradient.capacity() * sizeof(int32_t) +
           mActive.capacity() * sizeof(uint64_t) + mMasks.capacity() * sizeof(uint64_t) +
           mMaskOf.capacity() * sizeof(uint16_t) + mMaskOfMany.capacity() * sizeof(uint32_t);
}

} // namespace lsdem
