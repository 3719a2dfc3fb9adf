#include "SideLaneSums.h"

#include <type_traits>

namespace lsdem::contactlaw {

namespace {

/// Partial @a sum started at @a term (@a kStart) or added to.
template <bool kStart>
inline void put(double& sum, double term)
{
    if constexpr (kStart)
        sum = term;
    else
        sum += term;
}

/// Lanes [0, @a count) of springs @a s and normals @a n added to partials @a sum (indexed as
/// SideLaneSums::Sum), or the partials started with them (@a kStart: the side's first batch,
/// which spares zeroing them first), for bodies whose centroids are @a tester and @a other.
/// @a count is a std::integral_constant for a full batch, so that every loop's trip count is
/// known and each addition becomes a vector instruction over the lanes, or a plain int for a
/// part-filled batch. Each lane's terms are those of addSideForces and StiffnessSum::add
/// (ContactLaw.cpp). The pointers are restricted parameters (the partials, springs and normals
/// never overlap): without that promise the compiler must keep every addition in order with
/// every read. Not inlined: GCC keeps the promise only for the parameters of a function it
/// compiles as such.
template <bool kStart, typename Count>
[[gnu::noinline]] void addLanes(Count count, const ShearSpringLanes* __restrict s,
                                const NormalForceLanes* __restrict n,
                                double (*__restrict sum)[kShearLanes], const double tester[3],
                                const double other[3])
{
    using Sum = SideLaneSums;
    const double tx = tester[0], ty = tester[1], tz = tester[2];
    const double ox = other[0], oy = other[1], oz = other[2];
    for (int l = 0; l < count; ++l) {
        // The point force on the tester, normal and shear, and its moments about each centroid
        // (the other body feels the opposite force).
        const double fx = n->gx[l] + s->fx[l], fy = n->gy[l] + s->fy[l],
                     fz = n->gz[l] + s->fz[l];
        const double px = s->px[l], py = s->py[l], pz = s->pz[l];
        const double ax = px - tx, ay = py - ty, az = pz - tz;
        const double bx = px - ox, by = py - oy, bz = pz - oz;
        put<kStart>(sum[Sum::kForce][l], fx);
        put<kStart>(sum[Sum::kForce + 1][l], fy);
        put<kStart>(sum[Sum::kForce + 2][l], fz);
        put<kStart>(sum[Sum::kTesterTorque][l], ay * fz - az * fy);
        put<kStart>(sum[Sum::kTesterTorque + 1][l], az * fx - ax * fz);
        put<kStart>(sum[Sum::kTesterTorque + 2][l], ax * fy - ay * fx);
        put<kStart>(sum[Sum::kOtherTorque][l], -(by * fz - bz * fy));
        put<kStart>(sum[Sum::kOtherTorque + 1][l], -(bz * fx - bx * fz));
        put<kStart>(sum[Sum::kOtherTorque + 2][l], -(bx * fy - by * fx));
        // The stiffness: k'·n nᵀ, and per body k'·w wᵀ − k_t·r rᵀ and k_t·|r|².
        const double kt = s->stiffness[l], k = n->stiffness[l] - kt;
        const double nx = s->nx[l], ny = s->ny[l], nz = s->nz[l];
        const double knx = k * nx, kny = k * ny, knz = k * nz;
        put<kStart>(sum[Sum::kTranslation][l], knx * nx);
        put<kStart>(sum[Sum::kTranslation + 1][l], kny * nx);
        put<kStart>(sum[Sum::kTranslation + 2][l], knz * nx);
        put<kStart>(sum[Sum::kTranslation + 3][l], kny * ny);
        put<kStart>(sum[Sum::kTranslation + 4][l], knz * ny);
        put<kStart>(sum[Sum::kTranslation + 5][l], knz * nz);
        put<kStart>(sum[Sum::kShear][l], kt);
        const auto addLever = [&](int lower, int diagonal, double rx, double ry, double rz) {
            const double wx = ry * nz - rz * ny, wy = rz * nx - rx * nz, wz = rx * ny - ry * nx;
            const double kwx = k * wx, kwy = k * wy, kwz = k * wz;
            const double sx = -kt * rx, sy = -kt * ry, sz = -kt * rz;
            put<kStart>(sum[lower][l], kwx * wx + sx * rx);
            put<kStart>(sum[lower + 1][l], kwy * wx + sy * rx);
            put<kStart>(sum[lower + 2][l], kwz * wx + sz * rx);
            put<kStart>(sum[lower + 3][l], kwy * wy + sy * ry);
            put<kStart>(sum[lower + 4][l], kwz * wy + sz * ry);
            put<kStart>(sum[lower + 5][l], kwz * wz + sz * rz);
            put<kStart>(sum[diagonal][l], kt * (rx * rx + ry * ry + rz * rz));
        };
        addLever(Sum::kTesterLower, Sum::kTesterDiagonal, ax, ay, az);
        addLever(Sum::kOtherLower, Sum::kOtherDiagonal, bx, by, bz);
        put<kStart>(sum[Sum::kEnergy][l], n->energy[l] + s->energy[l]);
    }
}

} // namespace

void SideLaneSums::add(const ShearSpringLanes& springs, const NormalForceLanes& normals)
{
    const std::integral_constant<int, kShearLanes> all;
    if (mStarted) {
        addLanes<false>(all, &springs, &normals, mSum, mTester, mOther);
        return;
    }
    addLanes<true>(all, &springs, &normals, mSum, mTester, mOther);
    mStarted = true;
}

void SideLaneSums::addFirst(int count, const ShearSpringLanes& springs,
                            const NormalForceLanes& normals)
{
    if (mStarted) {
        addLanes<false>(count, &springs, &normals, mSum, mTester, mOther);
        return;
    }
    addLanes<true>(count, &springs, &normals, mSum, mTester, mOther);
    for (double(&partials)[kShearLanes] : mSum)
        for (int l = count; l < kShearLanes; ++l) partials[l] = 0.0;
    mStarted = true;
}

SideTotals SideLaneSums::totals() const
{
    static_assert(kShearLanes == 8, "the partials are joined pairwise, for eight lanes");
    if (!mStarted) return SideTotals();  // no contact carried a force
    const auto joined = [&](int sum) {
        const double* lane = mSum[sum];
        return ((lane[0] + lane[1]) + (lane[2] + lane[3])) +
               ((lane[4] + lane[5]) + (lane[6] + lane[7]));
    };
    const auto vector = [&](int first) {
        return Vec3(joined(first), joined(first + 1), joined(first + 2));
    };
    const auto lower = [&](int first) {
        LowerTriangle m;
        for (int i = 0; i < 6; ++i) m[static_cast<size_t>(i)] = joined(first + i);
        return m;
    };
    SideTotals t;
    t.forceOnTester = vector(kForce);
    t.torqueOnTester = vector(kTesterTorque);
    t.torqueOnOther = vector(kOtherTorque);
    t.translation = lower(kTranslation);
    t.shear = joined(kShear);
    t.testerLower = lower(kTesterLower);
    t.testerDiagonal = joined(kTesterDiagonal);
    t.otherLower = lower(kOtherLower);
    t.otherDiagonal = joined(kOtherDiagonal);
    t.elasticEnergy = joined(kEnergy);
    return t;
}

} // namespace lsdem::contactlaw
