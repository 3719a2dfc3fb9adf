/// @file LevelSetSampler.h
/// @brief Samples a grain's signed distance φ and the gradient ∇φ of its trilinear interpolant
///        from one 8-voxel fetch. A sampler is a pure function of a level set that is never
///        modified; it is cheap to make, so keep one per thread (the LevelSetCell overload
///        lets a caller keep corner values between calls).
#pragma once

#include "lsdem/ls/LevelSetCell.h"
#include "lsdem/ls/LevelSetGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace lsdem {

struct LevelSetSample
{
    double phi = 0.0;              ///< signed distance, negative inside (length)
    Vec3 gradient = Vec3::Zero();  ///< gradient of the trilinear interpolant (about unit length)
};

class LevelSetSampler
{
public:
    explicit LevelSetSampler(const LevelSetGrid& levelSet)
        : mBricks(levelSet.grid.get()), mBrickOrigin(levelSet.grid->origin()),
          mOrigin(levelSet.origin),
          mInvVoxel(1.0 / levelSet.voxelSize), mExact(levelSet.exact.get())
    {
    }

    /// φ and ∇φ at @a p (asset frame). Outside the band φ is the background (+band width) and
    /// the gradient is zero. The trilinear gradient jumps across cell faces; a point exactly on
    /// a face (nodes on a lattice aligned with the voxels hit this often) gets the mean of the
    /// two one-sided derivatives, so aligned configurations are not biased to one side.
    LevelSetSample sample(const Vec3& p)
    {
        LevelSetCell cell;
        return sample(p, cell);
    }

    /// The same as sample(p), reusing @a cell's corner values when @a p lies in that cell
    /// (and otherwise reading them into it): for a point sampled again at the next step.
    LevelSetSample sample(const Vec3& p, LevelSetCell& cell)
    {
        if (__builtin_expect(mExact != nullptr, 0)) return exactSample(p);
        const Vec3 index = (p - mOrigin) * mInvVoxel;
        const int lx = floorOf(index.x()), ly = floorOf(index.y()), lz = floorOf(index.z());
        const Vec3 base(lx, ly, lz);
        // Compared one by one, not as arrays: an array's comparison is a memcmp, which stores
        // the three indices and reads 8 bytes across two of those stores, a load the CPU cannot
        // forward from them (about 1 % of the slab's step, 2026-12-01).
        if (lx != cell.base[0] || ly != cell.base[1] || lz != cell.base[2]) {
            fetch(openvdb::Coord(lx, ly, lz), cell.value.data());
            cell.base = {lx, ly, lz};
        }
        const Vec3 fraction = index - base;
        LevelSetSample s = interpolate(cell.value.data(), fraction);
        if (__builtin_expect(
                onFace(fraction.x()) | onFace(fraction.y()) | onFace(fraction.z()), 0))
            averageAcrossFaces(index, base, fraction, s);
        return s;
    }

    /// The tangential part of φ's Hessian at @a p in the frame (@a t1, @a t2): ∇φ's change
    /// along each tangent by central differences @a h apart, H·t = (∇φ(p + h·t) − ∇φ(p −
    /// h·t))/2h, then {t₁·H·t₁, ½(t₂·H·t₁ + t₁·H·t₂), t₂·H·t₂} (four samples). Exact for an
    /// exact distance up to O(h²); from voxels each entry errs by O(1/R) node by node (the
    /// trilinear gradient jumps across cell faces).
    std::array<double, 3> tangentialHessian(const Vec3& p, const Vec3& t1, const Vec3& t2, double h)
    {
        auto change = [&](const Vec3& t) {
            return Vec3((sample(p + h * t).gradient - sample(p - h * t).gradient) / (2.0 * h));
        };
        const Vec3 along1 = change(t1), along2 = change(t2);
        return {t1.dot(along1), 0.5 * (t2.dot(along1) + t1.dot(along2)), t2.dot(along2)};
    }

    /// φ alone (same interpolant as sample()).
    double phi(const Vec3& p)
    {
        if (__builtin_expect(mExact != nullptr, 0)) return exactSample(p).phi;
        return evaluate((p - mOrigin) * mInvVoxel).phi;
    }

private:
    /// Within this many voxels of a cell face a point counts as on it (lattice-aligned nodes
    /// land there up to round-off); the one-sided derivatives are taken this far either side.
    static constexpr double kFaceTolerance = 1e-9;
    static constexpr double kFaceOffset = 1e-6;

    /// Whether a point whose fraction within its cell along an axis is @a f lies on a cell face:
    /// within the tolerance of 0 or 1 (the subtractions are exact, so this is |index −
    /// round(index)| ≤ tolerance).
    static bool onFace(double f) { return !(f > kFaceTolerance && 1.0 - f > kFaceTolerance); }

    /// ⌊x⌋ of an index within int's range, as std::floor gives it: the truncation, less one for
    /// a negative non-integer. Without SSE4.1 (the portable build) std::floor is a sequence of
    /// a dozen instructions, three times a sample.
    static int floorOf(double x)
    {
        const int truncated = static_cast<int>(x);
        return truncated - (x < static_cast<double>(truncated) ? 1 : 0);
    }

    /// @a s's gradient at a point on a cell face (index @a index, its cell's lower corner @a base
    /// and the @a fraction within it): along each axis whose fraction is on a face, the mean of
    /// the one-sided derivatives either side. Out of line: nodes seldom lie on a face, and its
    /// two samples an axis would otherwise enlarge the frame of every sample.
    [[gnu::noinline, gnu::cold]] void averageAcrossFaces(const Vec3& index, const Vec3& base,
                                                         const Vec3& fraction, LevelSetSample& s)
    {
        for (int axis = 0; axis < 3; ++axis) {
            const double f = fraction[axis];
            if (!onFace(f)) continue;
            const double face = f <= 0.5 ? base[axis] : base[axis] + 1.0;
            Vec3 before = index, after = index;
            before[axis] = face - kFaceOffset;
            after[axis] = face + kFaceOffset;
            s.gradient[axis] =
                0.5 * (evaluate(before).gradient[axis] + evaluate(after).gradient[axis]);
        }
    }

    /// The closed form's φ and ∇φ (kept out of line: the voxels' path is the hot one).
    [[gnu::noinline, gnu::cold]] LevelSetSample exactSample(const Vec3& p) const
    {
        return {mExact->phi(p), mExact->gradient(p)};
    }

    /// The trilinear interpolant and its gradient at an index-space point.
    LevelSetSample evaluate(const Vec3& index)
    {
        const openvdb::Coord lower(floorOf(index.x()), floorOf(index.y()), floorOf(index.z()));
        float value[8];
        fetch(lower, value);
        return interpolate(value, index - Vec3(lower.x(), lower.y(), lower.z()));
    }

    /// The trilinear interpolant of the cell corners @a value and its gradient at @a fraction.
    LevelSetSample interpolate(const float corner[8], const Vec3& fraction) const
    {
        double value[8];
        for (int k = 0; k < 8; ++k) value[k] = corner[k];
        const double fx = fraction.x(), fy = fraction.y(), fz = fraction.z();
        // Trilinear interpolation along x, then y, then z; corners indexed as (z<<2)|(y<<1)|x.
        const double c00 = value[0] + fx * (value[1] - value[0]);
        const double c10 = value[2] + fx * (value[3] - value[2]);
        const double c01 = value[4] + fx * (value[5] - value[4]);
        const double c11 = value[6] + fx * (value[7] - value[6]);
        const double c0 = c00 + fy * (c10 - c00);
        const double c1 = c01 + fy * (c11 - c01);
        LevelSetSample s;
        s.phi = c0 + fz * (c1 - c0);
        // Exact partial derivatives of the same trilinear polynomial.
        const double dx00 = value[1] - value[0], dx10 = value[3] - value[2];
        const double dx01 = value[5] - value[4], dx11 = value[7] - value[6];
        const double dx0 = dx00 + fy * (dx10 - dx00), dx1 = dx01 + fy * (dx11 - dx01);
        const double dy0 = c10 - c00, dy1 = c11 - c01;
        s.gradient = Vec3(dx0 + fz * (dx1 - dx0), dy0 + fz * (dy1 - dy0), c1 - c0) * mInvVoxel;
        return s;
    }

    /// The 8 corners of the cell whose lower corner is @a base.
    void fetch(const openvdb::Coord& base, float value[8]) const
    {
        // Read the corners straight from the bricks (4^3 voxels) that hold them: one brick
        // 3 times in 4 per axis, otherwise 2, 4 or 8 neighbouring bricks. Every place has a
        // brick (shared ones for uniform regions), so no corner needs a special case. Voxel
        // offsets within a brick are x*16 + y*4 + z, 3 bytes each (1 in narrow plane bricks, 2
        // in the others).
        using Bricks = LevelSetBricks;
        constexpr int kLog2 = Bricks::kLog2Dim, kLast = Bricks::kDim - 1;
        const openvdb::Coord local = base - mBrickOrigin;
        const int bx = local.x() >> kLog2, by = local.y() >> kLog2, bz = local.z() >> kLog2;
        const int cx = (local.x() & kLast) == kLast, cy = (local.y() & kLast) == kLast,
                  cz = (local.z() & kLast) == kLast;
        const uint32_t first = mBricks->brick(bx, by, bz);
        if (!(cx | cy | cz)) {
            const uint32_t b = first;
            const float step = mBricks->step(b);
            const int offset = Bricks::offset(local);
            if (mBricks->isWide(b)) {
                const uint8_t* d = mBricks->codes(b) + 3 * offset;
                constexpr int dx = 3 << (2 * kLog2), dy = 3 << kLog2, dz = 3;  // bytes
                value[0] = Bricks::decode(d, step);
                value[1] = Bricks::decode(d + dx, step);
                value[2] = Bricks::decode(d + dy, step);
                value[3] = Bricks::decode(d + dx + dy, step);
                value[4] = Bricks::decode(d + dz, step);
                value[5] = Bricks::decode(d + dx + dz, step);
                value[6] = Bricks::decode(d + dy + dz, step);
                value[7] = Bricks::decode(d + dx + dy + dz, step);
                return;
            }
            // A plane brick: the corners' integer plane plus their 8- or 16-bit codes, capped
            // at the band's edge; a deep brick: its base plus 16-bit codes (a flat plane).
            if (mBricks->isPlane(b)) {
                const int32_t* g = mBricks->gradient(b);
                const int32_t n = mBricks->base(b) + g[0] * (local.x() & kLast) +
                                  g[1] * (local.y() & kLast) + g[2] * (local.z() & kLast);
                if (mBricks->isNarrow(b))
                    planeCorners<uint8_t>(mBricks->codes(b) + offset, n, g, step, value);
                else
                    planeCorners<uint16_t>(mBricks->codes(b) + 2 * offset, n, g, step, value);
            } else {
                constexpr int32_t kFlat[3] = {0, 0, 0};
                planeCorners<uint16_t>(mBricks->codes(b) + 2 * offset, mBricks->base(b), kFlat,
                                       step, value);
            }
            return;
        }
        // Look up each distinct brick once: corner k lies in brick k's own place only along
        // the axes the cell crosses.
        uint32_t brick[8];
        brick[0] = first;
        brick[1] = cx ? mBricks->brick(bx + 1, by, bz) : brick[0];
        brick[2] = cy ? mBricks->brick(bx, by + 1, bz) : brick[0];
        brick[3] = cy ? (cx ? mBricks->brick(bx + 1, by + 1, bz) : brick[2]) : brick[1];
        if (cz) {
            brick[4] = mBricks->brick(bx, by, bz + 1);
            brick[5] = cx ? mBricks->brick(bx + 1, by, bz + 1) : brick[4];
            brick[6] = cy ? mBricks->brick(bx, by + 1, bz + 1) : brick[4];
            brick[7] = cy ? (cx ? mBricks->brick(bx + 1, by + 1, bz + 1) : brick[6]) : brick[5];
        } else {
            for (int k = 4; k < 8; ++k) brick[k] = brick[k - 4];
        }
        for (int corner = 0; corner < 8; ++corner) {
            const openvdb::Coord c = local.offsetBy(corner & 1, (corner >> 1) & 1, corner >> 2);
            value[corner] = mBricks->decode(brick[corner], Bricks::offset(c));
        }
    }

    /// The 8 corners of a cell within one deep or plane brick whose codes, of type @a Code,
    /// start at @a d for the cell's first corner, whose plane there is @a n, @a g its gradient.
    template <typename Code>
    void planeCorners(const uint8_t* d, int32_t n, const int32_t g[3], float step,
                      float value[8]) const
    {
        constexpr int kLog2 = LevelSetBricks::kLog2Dim, w = sizeof(Code);
        constexpr int dx = w << (2 * kLog2), dy = w << kLog2, dz = w;  // bytes
        const float ceiling = mBricks->planeCeiling();
        const auto at = [&](int bytes, int32_t plane) {
            Code q = 0;
            std::memcpy(&q, d + bytes, sizeof q);
            // exact, and capped, as decode()
            return std::min(static_cast<float>(n + plane + int32_t(q)) * step, ceiling);
        };
        value[0] = at(0, 0);
        value[1] = at(dx, g[0]);
        value[2] = at(dy, g[1]);
        value[3] = at(dx + dy, g[0] + g[1]);
        value[4] = at(dz, g[2]);
        value[5] = at(dx + dz, g[0] + g[2]);
        value[6] = at(dy + dz, g[1] + g[2]);
        value[7] = at(dx + dy + dz, g[0] + g[1] + g[2]);
    }

    const LevelSetBricks* mBricks;
    openvdb::Coord mBrickOrigin;  ///< index of the bricks' first voxel
    Vec3 mOrigin;
    double mInvVoxel;
    const ExactDistance* mExact;  ///< the level set's closed form, if it has one
};

} // namespace lsdem
