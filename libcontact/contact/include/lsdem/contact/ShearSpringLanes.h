/// @file ShearSpringLanes.h
/// @brief The shear springs of several node contacts at once. The contacts' fields lie side
///        by side in arrays, one "lane" per contact, so that the compiler computes several
///        springs with each vector instruction, and the roots and divisions of different
///        contacts overlap instead of each waiting on the one before (a spring's step is a
///        chain of two divisions and up to three roots; one contact at a time, that chain was
///        most of its cost). Each lane's arithmetic is updateShearForce's (TangentialModel.h),
///        operation for operation, so a lane gives the same bits as that function. Sums over
///        the contacts are not made here: for a side of 16 contacts or more the contact law
///        keeps one partial sum a lane (SideLaneSums.h, private to the library) and joins them
///        in a fixed order; for a smaller side it sums contact by contact.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem {

/// How many contacts' springs are computed together. Eight, not four: a batch's roots and
/// divisions wait on each other only within a lane, and the more lanes a batch has, the more
/// of them overlap (the slab's step 4.7 % faster, the law alone on a face of 64 or more
/// contacts 6–11 %; 2026-12-01).
inline constexpr int kShearLanes = 8;
/// The fewest contacts computed together: a part-filled batch computes its first four lanes
/// at once and the rest lane after lane, and a side of fewer contacts goes one by one.
inline constexpr int kShearLanesLeast = 4;

/// A body's motion over the step, as the slip of a material point needs it.
struct LaneBodyMotion
{
    double vx, vy, vz;  ///< centroid velocity
    double wx, wy, wz;  ///< angular velocity
    double cx, cy, cz;  ///< centroid
    /// From a body's velocity @a v, angular velocity @a w and centroid @a c.
    static LaneBodyMotion of(const Vec3& v, const Vec3& w, const Vec3& c)
    {
        return {v.x(), v.y(), v.z(), w.x(), w.y(), w.z(), c.x(), c.y(), c.z()};
    }
};

/// kShearLanes contacts' springs, field by field. A full batch is computed all lanes at once
/// (slips(), update()); a part-filled one four lanes at once, if it has them, and the rest lane
/// after lane (slipsFirst(), updateFirst()), where computing padding would cost more than the
/// vector instructions save.
struct ShearSpringLanes
{
    // In: where each contact acts and along which unit normal (pushing the tester out).
    alignas(32) double px[kShearLanes], py[kShearLanes], pz[kShearLanes];
    alignas(32) double nx[kShearLanes], ny[kShearLanes], nz[kShearLanes];
    // Out of slips(), in for update(): the relative displacement of the contact point over the
    // step, tester's minus other's.
    alignas(32) double ux[kShearLanes], uy[kShearLanes], uz[kShearLanes];
    // In for update(): the stored force carried into this step, its spring's stiffness k_t, and
    // Coulomb's limit μ·|F_n|.
    alignas(32) double sx[kShearLanes], sy[kShearLanes], sz[kShearLanes];
    alignas(32) double stiffness[kShearLanes];
    alignas(32) double limit[kShearLanes];
    // Out of update(): the new shear force, whether it slid (Coulomb's cap applied: 1, else 0),
    // what friction took if it slid, and the spring's energy ½|F_t|²/k_t.
    alignas(32) double fx[kShearLanes], fy[kShearLanes], fz[kShearLanes];
    alignas(32) double slid[kShearLanes];
    alignas(32) double dissipated[kShearLanes];
    alignas(32) double energy[kShearLanes];

    /// The slips u = (v_t(p) − v_o(p))·dt of every lane, from the tester's and the other
    /// body's motion (ContactGrain::pointVelocity's arithmetic).
    void slips(const LaneBodyMotion& tester, const LaneBodyMotion& other, double dt);
    /// The same for the first @a count lanes only (a part-filled batch).
    void slipsFirst(int count, const LaneBodyMotion& tester, const LaneBodyMotion& other, double dt);

    /// Every lane's spring carried through the step: updateShearForce(s, n, u, twist, k_t,
    /// limit) with twist = @a meanTurn · n, the pair's mean turn over the step about the normal.
    void update(const Vec3& meanTurn);

    /// The same for the first @a count lanes only (a side's last batch, if not full), with the
    /// same bits.
    void updateFirst(int count, const Vec3& meanTurn);
};

} // namespace lsdem
