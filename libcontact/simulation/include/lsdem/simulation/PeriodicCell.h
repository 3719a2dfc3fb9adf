/// @file PeriodicCell.h
/// @brief A periodic cell: along each axis given a period, space repeats with it, so a grain
///        near one face touches the images of the grains near the opposite face, and a grain
///        leaving through a face comes back through the other. Axes without a period are
///        ordinary (walls may bound them).
#pragma once

#include "lsdem/core/NumberText.h"
#include "lsdem/core/Vec3.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace lsdem {

struct PeriodicCell
{
    Vec3 origin = Vec3::Zero();
    Vec3 size = Vec3::Zero();  ///< the period along each axis; 0: not periodic along it
    /// How fast the cell stretches along each periodic axis (1/time, > 0 stretching): each
    /// step the cell and every grain's position in it are scaled from the origin by 1 + ε̇·dt
    /// (an affine deformation), the grains' velocities being what they have on top of it.
    Vec3 strainRate = Vec3::Zero();
    /// Stress control (a servo) along each periodic axis given a target > 0 (compressive,
    /// force/length²): each step the axis strains at maxStrainRate times the stress's relative
    /// error over `band` (clamped to ±1), stretching when the grains press harder than the
    /// target. Axes with target 0 keep strainRate as given.
    Vec3 targetStress = Vec3::Zero();
    Vec3 maxStrainRate = Vec3::Zero();
    static constexpr double band = 0.1;
    /// The stress the grains put on the cell at the last evaluation, along each axis
    /// (compressive positive): −M_kk / volume, M the Love–Weber stress moment of the contacts
    /// (zero unless the cell is periodic along all three axes, which gives the volume).
    Vec3 stress = Vec3::Zero();
    /// The least period the grains allow over their largest bounding radius: two grains reach
    /// 2r plus the contact list's skin (at most r/4), and twice that must fit the cell.
    static constexpr double kLeastSizeOverRadius = 4.5;
    /// The least period the grains allow (kLeastSizeOverRadius times the largest bounding
    /// radius, set when the world is built): a cell strained below it is refused.
    double leastSize = 0.0;

    bool active() const { return size.maxCoeff() > 0.0; }
    bool periodic(int axis) const { return size[axis] > 0.0; }
    bool deforming() const { return !strainRate.isZero(0.0) || servoed(); }
    /// The velocity of the cell's affine deformation at @a x (zero in a fixed cell).
    Vec3 affineVelocity(const Vec3& x) const { return strainRate.cwiseProduct(x - origin); }
    /// The shift of an image @a periods whole periods away along each axis.
    Vec3 imageShift(const Vec3& periods) const { return periods.cwiseProduct(size); }
    /// The first periodic axis of a cell of @a sizes below leastSize, or −1.
    int axisBelowLeastSize(const Vec3& sizes) const
    {
        for (int a = 0; a < 3; ++a)
            if (periodic(a) && sizes[a] < leastSize) return a;
        return -1;
    }
    /// What is wrong with a period below leastSize, in the words of every refusal of one.
    std::string leastSizeProblem() const
    {
        return "less than " + numberText(kLeastSizeOverRadius) +
               " times the largest grain's bounding radius (" +
               numberText(leastSize / kLeastSizeOverRadius) +
               "): a grain could touch two images of another";
    }
    /// Its volume (zero unless periodic along all three axes).
    double volume() const { return size.x() * size.y() * size.z(); }
    bool servoed() const { return targetStress.maxCoeff() > 0.0; }
    /// Set the strain rate of each stress-controlled axis from the stress now.
    void steer()
    {
        for (int a = 0; a < 3; ++a) {
            if (!(targetStress[a] > 0.0)) continue;
            const double error = (stress[a] - targetStress[a]) / (targetStress[a] * band);
            strainRate[a] = maxStrainRate[a] * std::clamp(error, -1.0, 1.0);
        }
    }

    /// The images of a point @a x that come within @a reach of the cell (its box widened by
    /// @a reach): their periods, −1 or 1 along some periodic axes and 0 along the others (the
    /// faces, edges and corners near @a x), the point itself not included.
    std::vector<Vec3> imagePeriodsNear(const Vec3& x, double reach) const
    {
        std::vector<Vec3> images;
        if (!active()) return images;
        for (int sx = -1; sx <= 1; ++sx)
            for (int sy = -1; sy <= 1; ++sy)
                for (int sz = -1; sz <= 1; ++sz) {
                    const Vec3 steps(sx, sy, sz);
                    if (steps.isZero()) continue;
                    bool near = true;
                    for (int a = 0; a < 3 && near; ++a) {
                        if (steps[a] == 0.0) continue;
                        const double shifted = x[a] + steps[a] * size[a];
                        near = periodic(a) && shifted >= origin[a] - reach &&
                               shifted <= origin[a] + size[a] + reach;
                    }
                    if (near) images.push_back(steps);
                }
        return images;
    }

    /// The whole periods that bring @a x into [origin, origin + size) along each periodic axis
    /// (zero along the others): x + shiftInto(x) is inside.
    Vec3 shiftInto(const Vec3& x) const
    {
        Vec3 shift = Vec3::Zero();
        for (int a = 0; a < 3; ++a) {
            if (!periodic(a)) continue;
            const double periods = std::floor((x[a] - origin[a]) / size[a]);
            double inside = x[a] - periods * size[a];
            double s = -periods * size[a];
            // (Rounding can leave it at origin + size exactly, or a hair below the origin.)
            if (inside >= origin[a] + size[a]) s -= size[a], inside -= size[a];
            if (inside < origin[a]) s += size[a];
            shift[a] = s;
        }
        return shift;
    }
};

} // namespace lsdem
