// The silo case's parking for grains that have left (SiloCase.cpp; private to the suite).
#pragma once

#include "lsdem/simulation/World.h"

#include <cmath>
#include <utility>
#include <vector>

namespace lsdem::verify {

/// Grains that have fallen well clear of the silo are set aside, fixed, on a grid far below
/// (inside the cylinder, which is unbounded, and apart from each other): they no longer fall,
/// collide or make the contact list rebuild, and keep their place in the world (and their
/// shear histories' indices).
class Parking
{
public:
    Parking(double siloRadius, double largestRadius) : mSpacing(2.5 * largestRadius)
    {
        const double reach = siloRadius - 2.0 * largestRadius;
        const int n = static_cast<int>(reach / mSpacing);
        for (int i = -n; i <= n; ++i)
            for (int j = -n; j <= n; ++j)
                if (std::hypot(i * mSpacing, j * mSpacing) <= reach)
                    mSlots.emplace_back(i * mSpacing, j * mSpacing);
    }
    void park(Grain& g)
    {
        const size_t layer = mUsed / mSlots.size(), k = mUsed % mSlots.size();
        g.body.pose.position =
            Vec3(mSlots[k].first, mSlots[k].second, -1000.0 - mSpacing * double(layer));
        g.body.velocity = Vec3::Zero();
        g.body.angularMomentum = Vec3::Zero();
        g.motion = GrainMotion::Fixed;
        ++mUsed;
    }

private:
    double mSpacing;
    std::vector<std::pair<double, double>> mSlots;
    size_t mUsed = 0;
};

} // namespace lsdem::verify
