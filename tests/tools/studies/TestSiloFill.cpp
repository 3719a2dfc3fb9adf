// The silo's settled fill as Beverloo's law reads it (studies/verify/SiloFill.h): its free
// surface and its core's bulk density, against a fill whose density is known by construction.
#include "studies/verify/SiloFill.h"

#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace lsdem;
using namespace lsdem::verify;

namespace {

/// Grain centres scattered uniformly through a silo of radius @a radius from the floor (the
/// plate's upper face) to @a height, @a perVolume of them per mm³, each of mass @a mass: a
/// fill of bulk density perVolume·mass by construction. (Points, not a packing: the estimator
/// counts centres, so this is what it sees of any fill.)
World uniformFill(const SiloPlan& p, double height, double perVolume, double mass)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double floor = 0.5 * p.plateThickness;
    const long long count = std::llround(perVolume * kPi * p.siloRadius * p.siloRadius * height);
    World w;
    w.grains.resize(size_t(count));
    for (Grain& g : w.grains) {
        const double r = p.siloRadius * std::sqrt(unit(random)), angle = 2.0 * kPi * unit(random);
        g.body.pose.position = Vec3(r * std::cos(angle), r * std::sin(angle), floor + height * unit(random));
        g.body.mass = mass;
    }
    return w;
}

} // namespace

// A fill of known density gives it back within its counting noise, and one grain lying five
// grain sizes above the surface moves neither the surface nor the density. Measured with the
// highest centre as the surface, that grain would stretch the core by 5 of its 7.5 mm with no
// more mass in it, and the density would come out 40 % low (C as much high).
// Tolerances: the core holds about 30,000 centres, so the count's own scatter is 0.6 %; 2 %
// is over three of those. The surface of 20 centres per mm³ lies within about 1/(20·4 mm²)
// = 0.0125 mm of a 2 mm column's top: 0.05 mm allows four times that.
TEST(SiloFill, OneGrainLyingHighMovesNeitherTheSurfaceNorTheDensity)
{
    SiloPlan p;
    p.siloRadius = 10.0;
    const double size = 1.0, height = 12.0, perVolume = 20.0, mass = 1.4e-9;
    World w = uniformFill(p, height, perVolume, mass);
    const double surface = 0.5 * p.plateThickness + height;
    EXPECT_NEAR(fillSurface(w, size), surface, 0.05);
    const double density = bulkDensity(w, p, size);
    EXPECT_NEAR(density, perVolume * mass, 0.02 * perVolume * mass);

    Grain high = w.grains.front();
    high.body.pose.position = Vec3(1.0, 2.0, surface + 5.0 * size);
    w.grains.push_back(high);
    EXPECT_NEAR(fillSurface(w, size), surface, 0.05);
    EXPECT_NEAR(bulkDensity(w, p, size), density, 0.002 * density);
}
