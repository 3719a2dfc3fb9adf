// The verification suite (lsdem-study verify): its references against forms worked out
// independently here (closed forms, a direct integration of Euler's equations, impulse
// balances), and the fast version of every case, which must pass every check it makes.
#include "studies/verify/BeverlooFit.h"
#include "studies/verify/FreeRotationReference.h"
#include "studies/verify/NormalImpactReference.h"
#include "studies/verify/RigidBodyTheory.h"
#include "studies/verify/VerifyStudy.h"

#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;
using namespace lsdem::verify;

// A linear spring (p = 1): δmax = v·sqrt(m/k), P = v·sqrt(m·k), t_c = π·sqrt(m/k), exactly;
// the same law given as a general force law (quadrature) and shifted by an onset (piecewise,
// the node sum's form) must agree.
TEST(VerifyReferences, LinearSpringImpactIsTheHarmonicHalfPeriod)
{
    const double m = 4e-6, k = 2e3, v = 1500.0;
    const NormalImpact closed = powerLawImpact(k, 1.0, m, v);
    EXPECT_NEAR(closed.maxOverlap, v * std::sqrt(m / k), 1e-12 * closed.maxOverlap);
    EXPECT_NEAR(closed.peakForce, v * std::sqrt(m * k), 1e-12 * closed.peakForce);
    EXPECT_NEAR(closed.contactTime, kPi * std::sqrt(m / k), 1e-12 * closed.contactTime);
    const NormalImpact quadrature =
        forceLawImpact([&](double d) { return k * d; }, m, v, 0.01);
    EXPECT_NEAR(quadrature.maxOverlap / closed.maxOverlap, 1.0, 1e-9);
    EXPECT_NEAR(quadrature.contactTime / closed.contactTime, 1.0, 1e-6);
    const double onset = 0.003;
    const NormalImpact shifted = piecewiseLawImpact(
        [&](double d) { return k * std::max(0.0, d - onset); },
        [&](double d) { return 0.5 * k * std::pow(std::max(0.0, d - onset), 2); }, onset, m, v,
        0.01);
    EXPECT_NEAR(shifted.maxOverlap, onset + closed.maxOverlap, 1e-9 * closed.maxOverlap);
    EXPECT_NEAR(shifted.contactTime / closed.contactTime, 1.0, 1e-6);
}

// The Winkler sphere's law P = κ·δ² (the adapted law on a wall): energy gives
// δmax = (3mv²/(2κ))^(1/3), and the contact lasts 2·(δmax/v)·∫₀¹ dx/sqrt(1 − x³), whose integral
// is B(1/3, 1/2)/3 = 1.4021821053254... (a value from the Beta function, not from the code).
TEST(VerifyReferences, WinklerSphereImpactMatchesItsEnergyAndBetaIntegral)
{
    const double m = 4.11e-6, kappa = kPi * 1e3 * 5.0, v = 3900.0;
    const NormalImpact r = powerLawImpact(kappa, 2.0, m, v);
    EXPECT_NEAR(r.maxOverlap, std::cbrt(1.5 * m * v * v / kappa), 1e-12 * r.maxOverlap);
    EXPECT_NEAR(r.contactTime, 2.0 * r.maxOverlap / v * 1.4021821053254, 1e-11 * r.contactTime);
    const NormalImpact q = forceLawImpact([&](double d) { return kappa * d * d; }, m, v, 0.01);
    EXPECT_NEAR(q.contactTime / r.contactTime, 1.0, 1e-6);
    EXPECT_NEAR(q.peakForce / r.peakForce, 1.0, 1e-9);
}

// K(0) = π/2; K(1/√2) = Γ(1/4)²/(4·sqrt(π)) = 1.8540746773013719 (the lemniscate case).
TEST(VerifyReferences, CompleteEllipticIntegralAtKnownPoints)
{
    EXPECT_NEAR(completeEllipticK(0.0), 0.5 * kPi, 1e-15);
    EXPECT_NEAR(completeEllipticK(1.0 / std::sqrt(2.0)), 1.8540746773013719, 1e-14);
}

// The flip time against Euler's equations integrated directly (classical Runge–Kutta, small
// steps): the time between two changes of sign of ω₂, on both sides of the separatrix.
TEST(VerifyReferences, FlipTimeMatchesEulersEquationsIntegrated)
{
    const Vec3 moments(4.3, 9.7, 11.3);
    for (const Vec3& omega : {Vec3(1.0, 100.0, 1.0), Vec3(30.0, 100.0, 0.5)}) {
        const auto rate = [&](const Vec3& w) {
            return Vec3((moments.y() - moments.z()) * w.y() * w.z() / moments.x(),
                        (moments.z() - moments.x()) * w.z() * w.x() / moments.y(),
                        (moments.x() - moments.y()) * w.x() * w.y() / moments.z());
        };
        const double h = 1e-6;
        Vec3 w = omega;
        double t = 0.0, previous = w.y();
        std::vector<double> crossings;
        while (crossings.size() < 3 && t < 10.0) {
            const Vec3 k1 = rate(w), k2 = rate(w + 0.5 * h * k1), k3 = rate(w + 0.5 * h * k2),
                       k4 = rate(w + h * k3);
            w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            t += h;
            if ((previous > 0.0) != (w.y() > 0.0))
                crossings.push_back(t - h + previous / (previous - w.y()) * h);
            previous = w.y();
        }
        ASSERT_EQ(crossings.size(), 3u);
        const double measured = 0.5 * (crossings[2] - crossings[0]);
        EXPECT_NEAR(intermediateAxisFlipTime(moments, omega) / measured, 1.0, 1e-6);
    }
}

// A solid ball on a wall: gross sliding takes μ·(1+e)·m·V_n of tangential momentum and gives
// 5/2 of it over R in spin; below the threshold tan θ = 3.5·μ·(1+e) the slip stops (5/7·v_t).
TEST(VerifyReferences, RigidImpactSlidesOrStopsTheSlip)
{
    const double m = 2.0, radius = 0.5, mu = 0.2, e = 0.8;
    ImpactBody ball;
    ball.mass = m;
    ball.inertia = 0.4 * m * radius * radius;
    ball.lever = Vec3(0, 0, -radius);
    ImpactBody wall;
    wall.movable = false;
    ball.velocity = Vec3(3.0, 0, -1.0);  // tan θ = 3 > 3.5·0.2·1.8 = 1.26: slides
    ImpactOutcome out = rigidImpact(ball, wall, Vec3::UnitZ(), e, mu);
    EXPECT_TRUE(out.slides);
    EXPECT_NEAR(out.first.velocity.x(), 3.0 - mu * (1 + e) * 1.0, 1e-14);
    EXPECT_NEAR(out.first.velocity.z(), e * 1.0, 1e-14);
    EXPECT_NEAR(out.first.angularVelocity.y(), 2.5 * mu * (1 + e) * 1.0 / radius, 1e-13);
    ball.velocity = Vec3(1.0, 0, -1.0);  // tan θ = 1 < 1.26: the slip stops
    out = rigidImpact(ball, wall, Vec3::UnitZ(), e, mu);
    EXPECT_FALSE(out.slides);
    EXPECT_NEAR(out.first.velocity.x(), 5.0 / 7.0, 1e-14);
    EXPECT_NEAR(out.slipAfter.norm(), 0.0, 1e-14);
    const SlideToRoll roll = slideToRoll(700.0, 0.25, 9810.0);
    EXPECT_NEAR(roll.slipTime, 2.0 * 700.0 / (7.0 * 0.25 * 9810.0), 1e-15);
    EXPECT_NEAR(roll.rollingSpeed, 500.0, 1e-12);
    EXPECT_EQ(inclineAcceleration(0.1, 0.3, 9810.0), 0.0);
    EXPECT_NEAR(inclineAcceleration(kPi / 6, 0.3, 9810.0),
                9810.0 * (0.5 - 0.3 * std::sqrt(3.0) / 2.0), 1e-11);
}

// Flows made by Beverloo's law itself (C 0.58, k 1.4, d 1.2, ρ_b 1.6e-9, g 9810) give back its
// C and k, a perfect line, and the exponent 5/2; a flow off the law shows in R².
TEST(VerifyReferences, BeverlooFitRecoversTheLawsConstants)
{
    const double c = 0.58, k = 1.4, d = 1.2, rho = 1.6e-9, g = 9810.0;
    std::vector<Discharge> flows;
    for (double diameter : {5.0, 6.5, 8.0, 9.5})
        flows.push_back({diameter, c * rho * std::sqrt(g) * std::pow(diameter - k * d, 2.5)});
    const BeverlooFit fit = fitBeverloo(flows, rho, g, d);
    EXPECT_NEAR(fit.c, c, 1e-12);
    EXPECT_NEAR(fit.k, k, 1e-10);
    EXPECT_NEAR(fit.rSquared, 1.0, 1e-12);
    EXPECT_NEAR(fittedExponent(flows, k * d), 2.5, 1e-12);
    // W ∝ D³ instead: W^(2/5) bends, and its own exponent is not 5/2.
    for (Discharge& f : flows) f.massFlow = 1e-9 * std::pow(f.diameter, 3.0);
    EXPECT_LT(fitBeverloo(flows, rho, g, d).rSquared, 0.9999);
    EXPECT_NEAR(fittedExponent(flows, 0.0), 3.0, 1e-12);
    // The line fit itself: y = 2x + 1 exactly, then one point off.
    const LineFit line = fitLine({0, 1, 2, 3}, {1, 3, 5, 7});
    EXPECT_NEAR(line.slope, 2.0, 1e-15);
    EXPECT_NEAR(line.intercept, 1.0, 1e-15);
    EXPECT_EQ(line.rSquared, 1.0);
    EXPECT_LT(fitLine({0, 1, 2, 3}, {1, 3, 6, 7}).rSquared, 0.99);
}

// The line's uncertainty, worked by hand for y = {1, 3, 6, 7} at x = {0, 1, 2, 3}: the line
// 2.1x + 1.1, residuals −0.1, −0.2, 0.7, −0.4, σ² = 0.70/2, Sxx = 5, x̄ = 1.5: Var(slope)
// 0.07, Var(intercept) 0.35·(1/4 + 2.25/5) = 0.245, Cov −1.5·0.35/5 = −0.105. Carried to
// Beverloo's C and k for the spheres' four silo flows (docs/verification.md): C's interval is
// the slope's t-interval mapped through C(s), k's is Fieller's for −intercept/slope, both
// computed apart with numpy (the same covariances as np.linalg.inv(XᵀX)·σ², t = 4.303) and
// Fieller's checked there by scanning θ for (b − θs)² ≤ t²·(Var b − 2θ·Cov + θ²·Var s):
// C 0.46529 in [0.33492, 0.62214], k 1.17007 in [0.40668, 1.76910]. The first-order
// half-widths used before (±0.1433, ±0.6711) were symmetric and wrong at both ends. Exact flows
// give intervals of zero width, two flows none, and a slope within its own noise an unbounded k.
TEST(VerifyReferences, BeverlooFitSaysHowLooselyTheFlowsFixCAndK)
{
    const LineFit line = fitLine({0, 1, 2, 3}, {1, 3, 6, 7});
    EXPECT_EQ(line.degreesOfFreedom, 2);
    EXPECT_NEAR(line.slopeVariance, 0.07, 1e-14);
    EXPECT_NEAR(line.interceptVariance, 0.245, 1e-14);
    EXPECT_NEAR(line.covariance, -0.105, 1e-14);

    const std::vector<Discharge> spheres = {
        {5.0, 2.013e-6}, {6.0, 3.578e-6}, {7.0, 5.984e-6}, {8.0, 8.472e-6}};
    const BeverlooFit fit = fitBeverloo(spheres, 1.532e-9, 9810.0, 1.0);
    EXPECT_NEAR(fit.c, 0.46529, 1e-5);
    EXPECT_NEAR(fit.cLow95, 0.33492, 1e-5);
    EXPECT_NEAR(fit.cHigh95, 0.62214, 1e-5);
    EXPECT_NEAR(fit.k, 1.17007, 1e-5);
    EXPECT_NEAR(fit.kLow95, 0.40668, 1e-5);
    EXPECT_NEAR(fit.kHigh95, 1.76910, 1e-5);

    const double c = 0.58, k = 1.4, d = 1.2, rho = 1.6e-9, g = 9810.0;
    std::vector<Discharge> exact;
    for (double diameter : {5.0, 6.5, 8.0})
        exact.push_back({diameter, c * rho * std::sqrt(g) * std::pow(diameter - k * d, 2.5)});
    const BeverlooFit exactFit = fitBeverloo(exact, rho, g, d);
    EXPECT_NEAR(exactFit.cLow95, c, 1e-6);
    EXPECT_NEAR(exactFit.cHigh95, c, 1e-6);
    EXPECT_NEAR(exactFit.kLow95, k, 1e-6);
    EXPECT_NEAR(exactFit.kHigh95, k, 1e-6);
    exact.pop_back();
    EXPECT_TRUE(std::isnan(fitBeverloo(exact, rho, g, d).cLow95));
    EXPECT_TRUE(std::isnan(fitBeverloo(exact, rho, g, d).kHigh95));
    // W^(2/5) = 1, 1.2, 0.9, 1.1: a slope of 0 against a standard error of 0.071.
    std::vector<Discharge> noise;
    for (const auto& [diameter, root] : {std::pair{5.0, 1.0}, {6.0, 1.2}, {7.0, 0.9}, {8.0, 1.1}})
        noise.push_back({diameter, std::pow(root, 2.5)});
    const BeverlooFit flat = fitBeverloo(noise, rho, g, d);
    EXPECT_TRUE(std::isinf(flat.kLow95) && flat.kLow95 < 0.0);
    EXPECT_TRUE(std::isinf(flat.kHigh95) && flat.kHigh95 > 0.0);
    EXPECT_EQ(flat.cLow95, 0.0);
    EXPECT_THROW(fitLine({1, 1}, {2, 3}), std::exception);
}

// The fast version of every case: each must make checks, and pass them all.
class VerifyCase : public ::testing::TestWithParam<std::string>
{
};

TEST_P(VerifyCase, PassesEveryCheckInItsFastVersion)
{
    VerifyOptions o;
    o.quick = true;
    o.cases = {GetParam()};
    const Report report = runVerification(o);
    ASSERT_FALSE(report.checks.empty());
    for (const Check& c : report.checks)
        EXPECT_TRUE(c.passes()) << c.caseName << " / " << c.formulation << " / " << c.quantity
                                << ": " << c.value << " against " << c.reference << " (error "
                                << c.error() << ", tolerance " << c.tolerance << "; " << c.basis
                                << ")";
}

INSTANTIATE_TEST_SUITE_P(Suite, VerifyCase, ::testing::ValuesIn([] {
                             std::vector<std::string> names;
                             for (const CaseEntry& e : caseList()) names.push_back(e.name);
                             return names;
                         }()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param;
                             for (char& ch : name) ch = ch == '-' ? '_' : ch;
                             return name;
                         });

// A bad case name or option is refused with the fix.
TEST(VerifyOptions, BadOptionsAreRefusedNamingTheFix)
{
    VerifyOptions o;
    o.cases = {"no-such-case"};
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.cases.clear();
    o.setup.sphereNodes = 10;
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.setup.sphereNodes = 4000;
    o.setup.sphereVoxel = 0.0;
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.setup.sphereVoxel = 0.1;
    EXPECT_NO_THROW(checkVerifyOptions(o));
    // The silo's orifices: between two grain sizes and 2/5 of the silo's width.
    o.siloOrifices = {5.0, 6.0};
    EXPECT_NO_THROW(checkVerifyOptions(o));
    o.siloOrifices = {5.0, 12.0};
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.siloOrifices = {1.0};
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    // A wider silo takes wider orifices (12 mm needs a radius of 15); its size within [4, 100].
    o.siloRadius = 15.0;
    o.siloOrifices = {5.0, 12.0};
    EXPECT_NO_THROW(checkVerifyOptions(o));
    o.siloRadius = 14.0;
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.siloRadius = 3.0;
    o.siloOrifices = {2.0};
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.siloRadius = 0.0;
    o.siloHeight = -1.0;
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
    o.siloHeight = 0.0;
    o.quick = true;
    o.siloOrifices = {8.0};
    EXPECT_THROW(checkVerifyOptions(o), std::exception);
}
