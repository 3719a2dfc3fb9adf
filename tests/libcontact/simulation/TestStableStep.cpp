// The stable step bounds of StableStep.h: the cheap bound the simulation screens grains with
// never exceeds the eigenvalue one, and is within its stated factor of it.
#include "lsdem/simulation/StableStep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace lsdem;

namespace {

/// A grain's stiffness from @a contacts random contacts on its surface (normal k, shear ks,
/// at a random point within a unit of the centroid): what Simulation sums.
GrainStiffness randomContacts(std::mt19937& random, int contacts)
{
    std::normal_distribution<double> gaussian;
    std::uniform_real_distribution<double> uniform(0.1, 10.0);
    GrainStiffness k;
    for (int c = 0; c < contacts; ++c) {
        const Vec3 n = Vec3(gaussian(random), gaussian(random), gaussian(random)).normalized();
        const Vec3 r(gaussian(random), gaussian(random), gaussian(random));
        const double kn = uniform(random), ks = 0.5 * uniform(random);
        const Mat3 spring = (kn - ks) * n * n.transpose() + ks * Mat3::Identity();
        // A spring at lever r: moment stiffness skew(r)ᵀ·K·skew(r).
        Mat3 lever;
        lever << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
        k.translation += spring;
        k.rotation += lever.transpose() * spring * lever;
    }
    return k;
}

} // namespace

TEST(StableStep, LowerBoundStaysBelowTheEigenvalueStepWithinItsFactor)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> inertia(0.2, 5.0), angle(0.0, 6.283185307179586);
    for (int trial = 0; trial < 500; ++trial) {
        RigidBody body;
        body.mass = inertia(random);
        body.principalInertia = Vec3(inertia(random), inertia(random), inertia(random));
        body.pose.orientation =
            Quat(Eigen::AngleAxisd(angle(random), Vec3(1.0, angle(random), -0.5).normalized()));
        const GrainStiffness k = randomContacts(random, 1 + trial % 6);
        const double beta = 0.1 * (trial % 4);
        const double exact = stableStep(k, body, beta);
        const double bound = stableStepLowerBound(k, body, beta);
        const double ratio = body.principalInertia.maxCoeff() / body.principalInertia.minCoeff();
        ASSERT_LE(bound, exact * (1.0 + 1e-12)) << "trial " << trial;
        ASSERT_GE(bound, exact / (std::pow(3.0, 0.25) * std::sqrt(ratio)) * (1.0 - 1e-12))
            << "trial " << trial;
    }
}

TEST(StableStep, LowerBoundIsExactForOneFrictionlessContactOnASphere)
{
    RigidBody ball;
    ball.mass = 3.0;
    ball.principalInertia = Vec3::Constant(1.2);
    GrainStiffness k;
    const Vec3 n = Vec3(1.0, 2.0, -2.0) / 3.0;
    k.translation = 50.0 * n * n.transpose();  // through the centre: no moment
    EXPECT_NEAR(stableStepLowerBound(k, ball, 0.2) / stableStep(k, ball, 0.2), 1.0, 1e-12);
    // And both are Verlet's 2/ω damped: 2/sqrt(k/m)·(sqrt(1 + β²) − β).
    EXPECT_NEAR(stableStep(k, ball, 0.2),
                2.0 / std::sqrt(50.0 / 3.0) * (std::sqrt(1.04) - 0.2), 1e-12);
}

TEST(StableStep, NoStiffnessAllowsAnyStep)
{
    RigidBody body;
    EXPECT_TRUE(std::isinf(stableStepLowerBound(GrainStiffness(), body, 0.3)));
    EXPECT_TRUE(std::isinf(stableStep(GrainStiffness(), body, 0.3)));
}

namespace {

/// Whether one degree of freedom (ω = 1, m = 1) stays bounded for 20,000 steps of @a dt in the
/// simulation's order: half kick, drift, the force at the new position with the half step's
/// velocity (spring, dashpot of ratio @a beta, then global damping @a lambda: each force 1 − λ
/// along the motion, 1 + λ against it), half kick.
bool boundedUnderGlobalDamping(double dt, double beta, double lambda)
{
    auto force = [&](double x, double v) {
        const double f = -x - 2.0 * beta * v;
        return f * v < 0.0 ? f * (1.0 + lambda) : f * v > 0.0 ? f * (1.0 - lambda) : f;
    };
    double x = 1.0, v = 0.0, f = force(x, v);
    for (int n = 0; n < 20000; ++n) {
        const double half = v + 0.5 * dt * f;
        x += dt * half;
        f = force(x, half);
        v = half + 0.5 * dt * f;
        if (!(std::abs(x) < 1e6)) return false;
    }
    return true;
}

/// The largest such dt, by bisection to 1e-6.
double criticalStepUnderGlobalDamping(double beta, double lambda)
{
    double stable = 0.01, unstable = 3.0;
    while (unstable - stable > 1e-6) {
        const double mid = 0.5 * (stable + unstable);
        (boundedUnderGlobalDamping(mid, beta, lambda) ? stable : unstable) = mid;
    }
    return stable;
}

} // namespace

// Global damping strengthens a force against the motion by 1 + λ: the step's limit falls to
// 2/(ω·√(1 + λ)) undamped. The limit stableStep gives must not exceed the one a direct
// simulation of the step finds, and lies within 0.1 % of it (without λ the check allowed
// ω·dt = 2 where the scheme fails at 1.754 for λ = 0.3, and 1.28 against 1.06 for β = 0.46).
TEST(StableStep, GlobalDampingShortensTheStepAsTheSchemeFindsIt)
{
    RigidBody body;
    body.mass = 1.0;
    body.principalInertia = Vec3::Ones();
    GrainStiffness k;
    k.translation = Vec3::UnitX() * Vec3::UnitX().transpose();  // ω = 1 along x
    for (const double lambda : {0.0, 0.3, 0.7})
        for (const double beta : {0.0, 0.2, 0.46}) {
            const double simulated = criticalStepUnderGlobalDamping(beta, lambda);
            const double limit = stableStep(k, body, beta, lambda);
            EXPECT_LE(limit, simulated * (1.0 + 1e-5)) << lambda << " " << beta;
            EXPECT_GT(limit, 0.999 * simulated) << lambda << " " << beta;
            EXPECT_NEAR(stableStepLowerBound(k, body, beta, lambda), limit, 1e-12 * limit);
        }
}
