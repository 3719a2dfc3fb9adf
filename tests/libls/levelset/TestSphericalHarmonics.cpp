// Real spherical harmonics against their definition: orthonormal on the sphere (by quadrature
// exact for the products: Gauss–Legendre in cos θ, the trapezoid rule in φ), and the closed
// forms of the first degrees.
#include "lsdem/ls/SphericalHarmonics.h"

#include "lsdem/core/Constants.h"
#include "lsdem/ls/GaussLegendre.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

TEST(SphericalHarmonics, AreOrthonormalOnTheSphere)
{
    const int L = 10;
    const int count = (L + 1) * (L + 1);
    // Products have degree <= 2L in cos θ (times sin^k θ, even powers are polynomials; odd
    // ones pair up with an odd partner) and frequency <= 2L in φ: 2L + 2 points in each.
    std::vector<double> x, w;
    gaussLegendre(2 * L + 2, x, w);
    const int nPhi = 2 * L + 2;
    std::vector<double> gram(static_cast<size_t>(count * count), 0.0), y;
    for (size_t i = 0; i < x.size(); ++i)
        for (int j = 0; j < nPhi; ++j) {
            realSphericalHarmonics(L, std::acos(x[i]), 2.0 * kPi * j / nPhi, y);
            const double weight = w[i] * 2.0 * kPi / nPhi;
            for (int a = 0; a < count; ++a)
                for (int b = 0; b < count; ++b)
                    gram[static_cast<size_t>(a * count + b)] += weight * y[a] * y[b];
        }
    for (int a = 0; a < count; ++a)
        for (int b = 0; b < count; ++b)
            EXPECT_NEAR(gram[static_cast<size_t>(a * count + b)], a == b ? 1.0 : 0.0, 1e-12)
                << a << " " << b;
}

TEST(SphericalHarmonics, FirstDegreesMatchTheirClosedForms)
{
    std::vector<double> y;
    const double theta = 0.7, phi = -2.1;
    realSphericalHarmonics(2, theta, phi, y);
    const double c = std::cos(theta), s = std::sin(theta);
    EXPECT_NEAR(y[harmonicIndex(0, 0)], 0.5 / std::sqrt(kPi), 1e-15);
    EXPECT_NEAR(y[harmonicIndex(1, 0)], std::sqrt(3.0 / (4 * kPi)) * c, 1e-15);
    EXPECT_NEAR(y[harmonicIndex(1, 1)], std::sqrt(3.0 / (4 * kPi)) * s * std::cos(phi), 1e-15);
    EXPECT_NEAR(y[harmonicIndex(1, -1)], std::sqrt(3.0 / (4 * kPi)) * s * std::sin(phi), 1e-15);
    EXPECT_NEAR(y[harmonicIndex(2, 0)], std::sqrt(5.0 / (16 * kPi)) * (3 * c * c - 1), 1e-15);
    EXPECT_NEAR(y[harmonicIndex(2, 2)],
                std::sqrt(15.0 / (16 * kPi)) * s * s * std::cos(2 * phi), 1e-15);
}
