// The exact two-sphere reference against an independent quadrature and the small-δ limit.
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/core/Constants.h"

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
/// kn*·d along the normal of sphere j, projected on the centre line, times 2πR² sin θ dθ; or
/// with @a projected false, the volume law's kv·d (its force lies along the line by symmetry).
double referenceForce(double r, double delta, double k, bool projected = true)
{
    const double h = 2 * r - delta;
    const double thetaMax = std::acos(h / (2 * r));
    auto f = [&](double theta) {
        const double x = r * std::sin(theta), z = r * std::cos(theta);  // on sphere i
        const double dz = h - z;                                          // towards j's centre
        const double rho = std::hypot(x, dz);                              // distance to j's centre
        const double depth = r - rho;
        const double alongLine = projected ? dz / rho : 1.0;  // j's inward normal's part on e
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

// The volume law's limit kv ∫ d dA: the same independent quadrature without the projection on
// the line of centres, and larger than the adapted force by δ/(6R) to leading order (the
// normals of sphere j tilt from the line by about r/R at distance r from it, so n·e ≈ 1 − r²/(2R²),
// and weighting that with d over the cap gives δ/(6R)).
TEST(SphereContactReference, VolumeLawMatchesAnIndependentQuadrature)
{
    for (double delta : {0.001, 0.01, 0.1, 0.5, 2.0}) {
        const double ref = referenceForce(5.0, delta, 1e3, false);
        EXPECT_NEAR(lsdem::exactSphereVolumeForce(5.0, delta, 1e3), ref, 1e-9 * ref) << delta;
    }
    EXPECT_EQ(lsdem::exactSphereVolumeForce(5.0, 0.0, 1e3), 0.0);
    for (double delta : {0.01, 0.001}) {
        const double excess = lsdem::exactSphereVolumeForce(5.0, delta, 1e3) /
                                  lsdem::exactSphereContactForce(5.0, delta, 1e3) - 1.0;
        EXPECT_NEAR(excess, delta / (6 * 5.0), 0.05 * delta / (6 * 5.0)) << delta;
    }
}
