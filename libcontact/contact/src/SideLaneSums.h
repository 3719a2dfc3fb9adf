// What a side of a contact adds up over its point forces when they come kShearLanes at a time
// (ShearSpringLanes.h): the force and moments on both bodies, the stiffness the stability check
// needs, and the elastic energy. Private to lsdem_contact.
//
// Each sum is kept as kShearLanes partial sums, one a lane: the batch's lanes add into them
// side by side, so the compiler makes vector instructions of the additions, and each partial
// waits only on its own last addition rather than on every contact before it. The partials are
// joined once, at the side's end, always pairwise by lane number: ((0 + 1) + (2 + 3)) + ((4 + 5)
// + (6 + 7)). The order is fixed by the contacts' order alone, so the result is the same on any
// number of threads; it differs from a sum made contact by contact in rounding only (a few ulps
// of the sum).
#pragma once

#include "lsdem/contact/ShearSpringLanes.h"

#include <array>

namespace lsdem::contactlaw {

/// A batch's normal forces beside its shear springs (ShearSpringLanes): per lane, the normal
/// law's point force on the tester, its stiffness k_n, and its spring's energy ½k_n·d².
struct NormalForceLanes
{
    alignas(32) double gx[kShearLanes], gy[kShearLanes], gz[kShearLanes];
    alignas(32) double stiffness[kShearLanes];
    alignas(32) double energy[kShearLanes];
};

/// A lower triangle of a symmetric 3×3 matrix: xx, yx, zx, yy, zy, zz.
using LowerTriangle = std::array<double, 6>;

/// The sums of one side once its lanes are joined. Force and moments act on the side's tester
/// (moments about its centroid) and on the other body (about the other's centroid); the
/// stiffness is in StiffnessSum's terms: Σ k'·n nᵀ and Σ k_t for translation, and for rotation
/// about each centroid Σ k'·w wᵀ − k_t·r rᵀ and Σ k_t·|r|² (k' = k_n − k_t, r the lever,
/// w = r × n).
struct SideTotals
{
    Vec3 forceOnTester = Vec3::Zero();
    Vec3 torqueOnTester = Vec3::Zero(), torqueOnOther = Vec3::Zero();
    LowerTriangle translation{};
    double shear = 0.0;
    LowerTriangle testerLower{}, otherLower{};
    double testerDiagonal = 0.0, otherDiagonal = 0.0;
    double elasticEnergy = 0.0;
};

/// The partial sums of a side (above).
class SideLaneSums
{
public:
    /// For a side whose tester's centroid is @a testerCentre and the other body's
    /// @a otherCentre.
    SideLaneSums(const Vec3& testerCentre, const Vec3& otherCentre)
        : mTester{testerCentre.x(), testerCentre.y(), testerCentre.z()},
          mOther{otherCentre.x(), otherCentre.y(), otherCentre.z()}
    {
    }

    /// A full batch: every lane's total point force (normal plus shear) at its point, its
    /// stiffness and energies, added to that lane's partials.
    void add(const ShearSpringLanes& springs, const NormalForceLanes& normals);
    /// The same for the first @a count lanes of a part-filled batch.
    void addFirst(int count, const ShearSpringLanes& springs, const NormalForceLanes& normals);

    /// The partials joined, lane 0 to the last, in a fixed order.
    SideTotals totals() const;

    /// Which sum an index of mSum is: three force components, the two moments' three each, the
    /// translation's six, Σ k_t, each body's six and its diagonal, and the energy.
    enum Sum : int
    {
        kForce = 0,
        kTesterTorque = 3,
        kOtherTorque = 6,
        kTranslation = 9,
        kShear = 15,
        kTesterLower = 16,
        kTesterDiagonal = 22,
        kOtherLower = 23,
        kOtherDiagonal = 29,
        kEnergy = 30,
        kSumCount = 31
    };

private:
    double mTester[3], mOther[3];  ///< the centroids
    alignas(32) double mSum[kSumCount][kShearLanes];  ///< started by the first batch
    bool mStarted = false;
};

} // namespace lsdem::contactlaw
