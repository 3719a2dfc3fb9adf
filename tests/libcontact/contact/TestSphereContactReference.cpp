// The exact two-sphere reference against an independent quadrature and the small-δ limit.
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/ls/Constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace {

using lsdem::kPi;

/// Adaptive Simpson on [a, b]: an independent method from the library's Gauss–Legendre.
double simpson(const std::function<double(double)>& f, double a, double b, double tol, int depth = 0)
{
    const double m = 0.5 * (a + b);
    const double whole = (b - a) / 6 * (f(a) + 4 * f(m) + f(b));
    const double left = (m - a) / 6 * (f(a) + 4 * f(0.5 * (a + m)) + f(m));
    const double right = (b - m) / 6 * (f(m) + 4 * f(0.5 * (m + b)) + f(b));
    if (depth > 30 || std::abs(left + right - whole) < 15 * tol) return left + right;
    return simpson(f, a, m, tol / 2, depth + 1) + simpson(f, m, b, tol / 2, depth + 1);
}

/// P by integrating over the polar angle θ of sphere i directly (not u = cos θ): the traction
/// kn*·d along the normal of sphere j, projected on the centre line, times 2πR² sin θ dθ.
double referenceForce(double r, double delta, double k)
{
    const double h = 2 * r - delta;
    const double thetaMax = std::acos(h / (2 * r));
    auto f = [&](double theta) {
        const double x = r * std::sin(theta), z = r * std::cos(theta);  // on sphere i
        const double dz = h - z;                                          // towards j's centre
        const double rho = std::hypot(x, dz);                              // distance to j's centre
        const double depth = r - rho;
        const double alongLine = dz / rho;  // component of j's outward normal, reversed, on e
        return k * depth * alongLine * 2 * kPi * r * r * std::sin(theta);
    };
    return simpson(f, 0.0, thetaMax, 1e-12 * k * r * delta * delta);  // relative to P ~ kRδ²
}

} // namespace

TEST(SphereContactReference, MatchesAnIndependentQuadrature)
{
    for (double delta : {0.001, 0.01, 0.1, 0.5, 2.0}) {
        const double ref = referenceForce(5.0, delta, 1e3);
        EXPECT_NEAR(lsdem::exactSphereContactForce(5.0, delta, 1e3), ref, 1e-9 * ref) << delta;
    }
    EXPECT_EQ(lsdem::exactSphereContactForce(5.0, 0.0, 1e3), 0.0);
}

TEST(SphereContactReference, ApproachesTheLeadingOrderForSmallOverlap)
{
    // The relative correction to (π/2) k R δ² is O(δ/R).
    for (double delta : {0.1, 0.01, 0.001}) {
        const double exact = lsdem::exactSphereContactForce(5.0, delta, 1e3);
        const double leading = lsdem::leadingOrderSphereContactForce(5.0, delta, 1e3);
        EXPECT_NEAR(exact / leading, 1.0, delta / 5.0) << delta;
    }
}
