#include "lsdem/contact/ShearSpringLanes.h"

#include <cmath>
#include <type_traits>

// Built with -fno-math-errno and -fno-trapping-math (CMakeLists.txt), without which GCC keeps
// these loops scalar. The values do not change.

namespace lsdem {

namespace {

/// The slips of lanes [@a begin, @a end) of @a s (ShearSpringLanes::slips); the bounds as in
/// updateSprings.
template <typename Begin, typename End>
void slipsOf(ShearSpringLanes& s, Begin begin, End end, const LaneBodyMotion& a,
             const LaneBodyMotion& b, double dt)
{
    for (int l = begin; l < end; ++l) {
        // v + ω × (p − c) of each body, as ContactGrain::pointVelocity.
        const double ax = s.px[l] - a.cx, ay = s.py[l] - a.cy, az = s.pz[l] - a.cz;
        const double bx = s.px[l] - b.cx, by = s.py[l] - b.cy, bz = s.pz[l] - b.cz;
        const double vax = a.vx + (a.wy * az - a.wz * ay), vay = a.vy + (a.wz * ax - a.wx * az),
                     vaz = a.vz + (a.wx * ay - a.wy * ax);
        const double vbx = b.vx + (b.wy * bz - b.wz * by), vby = b.vy + (b.wz * bx - b.wx * bz),
                     vbz = b.vz + (b.wx * by - b.wy * bx);
        s.ux[l] = (vax - vbx) * dt;
        s.uy[l] = (vay - vby) * dt;
        s.uz[l] = (vaz - vbz) * dt;
    }
}

/// The springs of lanes [@a begin, @a end) of @a s (ShearSpringLanes::update). The bounds are
/// either std::integral_constants, so that the loops have a trip count known at compile time
/// and become vector instructions, or plain ints for the rest of a part-filled batch, lane
/// after lane.
template <typename Begin, typename End>
void updateSprings(ShearSpringLanes& s, Begin begin, End end, const Vec3& meanTurn)
{
    const double mx = meanTurn.x(), my = meanTurn.y(), mz = meanTurn.z();
    alignas(32) double storedSquare[kShearLanes], trialSquare[kShearLanes];
    int anySliding = 0;
    for (int l = begin; l < end; ++l) {
        const double n0 = s.nx[l], n1 = s.ny[l], n2 = s.nz[l];
        const double s0 = s.sx[l], s1 = s.sy[l], s2 = s.sz[l];
        const double k = s.stiffness[l], cap = s.limit[l];
        // Onto the new tangent plane, then turned about the normal by the pair's mean spin,
        // and brought back to the stored size.
        const double twist = (mx * n0 + my * n1) + mz * n2;
        const double along = (s0 * n0 + s1 * n1) + s2 * n2;
        double h0 = s0 - along * n0, h1 = s1 - along * n1, h2 = s2 - along * n2;
        const double c0 = n1 * h2 - n2 * h1, c1 = n2 * h0 - n0 * h2, c2 = n0 * h1 - n1 * h0;
        h0 += twist * c0;
        h1 += twist * c1;
        h2 += twist * c2;
        const double before2 = (s0 * s0 + s1 * s1) + s2 * s2;
        const double after2 = (h0 * h0 + h1 * h1) + h2 * h2;
        // Both sides of each choice are computed and one is picked, so that the loop has no
        // branches; a value not picked may be NaN or infinite.
        const double back = std::sqrt(before2 / after2);
        const double keep = after2 > 0.0 ? back : 1.0;
        h0 *= keep;
        h1 *= keep;
        h2 *= keep;
        // Loaded by the tangential slip.
        const double slipAlong = (s.ux[l] * n0 + s.uy[l] * n1) + s.uz[l] * n2;
        h0 -= k * (s.ux[l] - slipAlong * n0);
        h1 -= k * (s.uy[l] - slipAlong * n1);
        h2 -= k * (s.uz[l] - slipAlong * n2);
        const double size2 = (h0 * h0 + h1 * h1) + h2 * h2;
        const bool sliding = (cap < 0.0) | (size2 > cap * cap);
        anySliding |= sliding ? 1 : 0;
        s.slid[l] = sliding ? 1.0 : 0.0;
        s.dissipated[l] = 0.0;
        storedSquare[l] = before2;
        trialSquare[l] = size2;
        s.fx[l] = h0;
        s.fy[l] = h1;
        s.fz[l] = h2;
    }
    // Coulomb's cap, where some spring slides (its roots and divisions are not needed where
    // all stick, the common case of a contact at rest).
    if (anySliding != 0) {
        for (int l = begin; l < end; ++l) {
            const bool sliding = s.slid[l] != 0.0;
            const double cap = s.limit[l];
            const double trial = std::sqrt(trialSquare[l]), capped = cap > 0.0 ? cap : 0.0;
            const double toCap = cap / trial;
            const double scale = sliding ? (cap > 0.0 ? toCap : 0.0) : 1.0;
            s.fx[l] *= scale;
            s.fy[l] *= scale;
            s.fz[l] *= scale;
            const double stored = std::sqrt(storedSquare[l]);
            const double least = trial < stored ? trial : stored;  // std::min(stored, trial)
            const double lost = (trial - capped) * 0.5 * (capped + least) / s.stiffness[l];
            s.dissipated[l] = sliding ? lost : 0.0;
        }
    }
    for (int l = begin; l < end; ++l) {
        const double size2 = (s.fx[l] * s.fx[l] + s.fy[l] * s.fy[l]) + s.fz[l] * s.fz[l];
        s.energy[l] = 0.5 * size2 / s.stiffness[l];
    }
}

template <int kLanes>
using Lanes = std::integral_constant<int, kLanes>;

/// A part-filled batch of @a count lanes through @a kernel(begin, end): the first
/// kShearLanesLeast lanes at once and the rest lane after lane, or all lane after lane if it
/// has fewer.
template <typename Kernel>
void firstLanes(int count, Kernel kernel)
{
    if (count < kShearLanesLeast) {
        kernel(0, count);
        return;
    }
    kernel(Lanes<0>(), Lanes<kShearLanesLeast>());
    kernel(kShearLanesLeast, count);
}

} // namespace

void ShearSpringLanes::slips(const LaneBodyMotion& tester, const LaneBodyMotion& other, double dt)
{
    slipsOf(*this, Lanes<0>(), Lanes<kShearLanes>(), tester, other, dt);
}

void ShearSpringLanes::slipsFirst(int count, const LaneBodyMotion& tester,
                                  const LaneBodyMotion& other, double dt)
{
    firstLanes(count, [&](auto begin, auto end) { slipsOf(*this, begin, end, tester, other, dt); });
}

void ShearSpringLanes::update(const Vec3& meanTurn)
{
    updateSprings(*this, Lanes<0>(), Lanes<kShearLanes>(), meanTurn);
}

void ShearSpringLanes::updateFirst(int count, const Vec3& meanTurn)
{
    firstLanes(count, [&](auto begin, auto end) { updateSprings(*this, begin, end, meanTurn); });
}

} // namespace lsdem
