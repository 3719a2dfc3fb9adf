// The stable step bounds of StableStep.h: the cheap bound the simulation screens grains with
// never exceeds the eigenvalue one, and is within its stated factor of it.
#include "lsdem/simulation/StableStep.h"

#include <Eigen/Eigenvalues>
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

TEST(StableStep, LowerBoundIsCloseForAGrainHeldAlikeOnEverySide)
{
    // A ball pressed by six like contacts (±x, ±y, ±z of a frame turned at random, each with
    // shear springs) has one stiffness along every axis, and Frobenius's norm is √3 times it:
    // a lower bound from that norm is 3^(-1/4) = 0.76 of the step, below the least limit of a
    // packing of like grains, so every grain's eigenvalues were needed at every step.
    // Gershgorin's row sums (and the traces' bound) are exact for a multiple of the identity
    // in any frame, and within a hair of it for a ball whose contacts differ slightly.
    std::mt19937 random(3);
    std::uniform_real_distribution<double> spread(0.99, 1.01), angle(0.0, 6.283185307179586);
    RigidBody ball;
    ball.mass = 2.0;
    ball.principalInertia = Vec3::Constant(0.8);
    for (int trial = 0; trial < 50; ++trial) {
        const Mat3 turn =
            Eigen::AngleAxisd(angle(random), Vec3(1.0, angle(random), -2.0).normalized())
                .toRotationMatrix();
        GrainStiffness k;
        for (int axis = 0; axis < 3; ++axis)
            for (double side : {1.0, -1.0}) {
                const Vec3 n = side * (turn * Vec3::Unit(axis));
                const double kn = 100.0 * spread(random), ks = 50.0 * spread(random);
                const Vec3 r = -n;  // the contact at the ball's surface, radius 1
                Mat3 lever;
                lever << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
                const Mat3 spring = (kn - ks) * n * n.transpose() + ks * Mat3::Identity();
                k.translation += spring;
                k.rotation += lever.transpose() * spring * lever;
            }
        const double exact = stableStep(k, ball, 0.3);
        EXPECT_LE(stableStepLowerBound(k, ball, 0.3), exact);
        EXPECT_GT(stableStepLowerBound(k, ball, 0.3), 0.99 * exact) << "trial " << trial;
    }
}

TEST(StableStep, LowerBoundIsExactWhereTheTwoSmallerEigenvaluesMeet)
{
    // A stiffness of eigenvalues (2, 1, 1)·c in a frame turned at random (as a grain whose
    // contacts are stiffer along one direction): Frobenius's norm is √6·c and Gershgorin's row
    // sums up to about 1.2 times the eigenvalue, but the traces' bound is exact.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
    RigidBody ball;
    ball.mass = 1.5;
    ball.principalInertia = Vec3::Constant(0.7);
    for (int trial = 0; trial < 50; ++trial) {
        const Mat3 turn =
            Eigen::AngleAxisd(angle(random), Vec3(angle(random), 1.0, -1.0).normalized())
                .toRotationMatrix();
        const Mat3 stiffness = 40.0 * turn * Vec3(2.0, 1.0, 1.0).asDiagonal() * turn.transpose();
        GrainStiffness k;
        k.translation = stiffness;
        k.rotation = 0.3 * stiffness;
        const double exact = stableStep(k, ball, 0.2);
        EXPECT_LE(stableStepLowerBound(k, ball, 0.2), exact);
        EXPECT_GT(stableStepLowerBound(k, ball, 0.2), 0.9999 * exact) << "trial " << trial;
    }
}

TEST(StableStep, LowerBoundStaysBelowTheEigenvalueStepWhereTheEigenvaluesNearlyMeet)
{
    // Where the traces' bound is tight, round-off decides which side of the eigenvalue it
    // falls: stiffnesses c·I + ε·(a random contact), with ε from 1e-14 to 1e-2 of c, in random
    // frames. A bound above the exact step would let the screen pass a grain the exact limit
    // fails.
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    RigidBody ball;
    ball.mass = 1.7;
    ball.principalInertia = Vec3::Constant(0.6);
    for (int trial = 0; trial < 2000; ++trial) {
        const double epsilon = std::pow(10.0, -14.0 + 12.0 * unit(random));
        const double c = std::pow(10.0, -3.0 + 9.0 * unit(random));
        GrainStiffness k = randomContacts(random, 1 + trial % 3);
        k.translation = c * (Mat3::Identity() + epsilon * k.translation / k.translation.norm());
        k.rotation = c * (Mat3::Identity() + epsilon * k.rotation / k.rotation.norm());
        ASSERT_LE(stableStepLowerBound(k, ball, 0.0), stableStep(k, ball, 0.0))
            << "trial " << trial << ", epsilon " << epsilon;
    }
}

TEST(StableStep, RotationCountsInAnyUnits)
{
    // A grain a tenth of a millimetre across in SI units: its rotational stiffness, 1e-13
    // N·m/rad, is tiny as a number but sets the step (ω² = 1e-13/1e-21 = 1e8 against the
    // translation's 1e-5/1e-12 = 1e7). Undamped, the step is Verlet's 2/ω with ω² their sum.
    RigidBody grain;
    grain.mass = 1e-12;
    grain.principalInertia = Vec3::Constant(1e-21);
    GrainStiffness k;
    k.translation = 1e-5 * Mat3::Identity();
    k.rotation = 1e-13 * Mat3::Identity();
    EXPECT_NEAR(stableStep(k, grain, 0.0) * std::sqrt(1.1e8), 2.0, 1e-9);
    EXPECT_LE(stableStepLowerBound(k, grain, 0.0), stableStep(k, grain, 0.0));
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

namespace {

/// A rigid body's 6 degrees of freedom near rest (translation, then rotation in its principal
/// frame) on linear springs and dashpots: mass, stiffness and damping matrices.
struct LinearGrain
{
    Eigen::Matrix<double, 6, 1> mass;
    Eigen::Matrix<double, 6, 6> stiffness = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 6> damping = Eigen::Matrix<double, 6, 6>::Zero();
    GrainStiffness sums;  ///< the same contacts as the stability check sums them
};

/// Adds a contact at lever @a r with normal @a n: a spring kn along n and ks across it, and a
/// dashpot c along n at the same point. A point of the body at r moves by u + θ × r = B·(u, θ),
/// so the contact adds Bᵀ·K·B and Bᵀ·c·n nᵀ·B.
void addContact(LinearGrain& g, const Vec3& r, const Vec3& n, double kn, double ks, double c)
{
    Eigen::Matrix<double, 3, 6> b;
    Mat3 lever;  // lever·v = r × v
    lever << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    b << Mat3::Identity(), lever.transpose();
    const Mat3 spring = (kn - ks) * n * n.transpose() + ks * Mat3::Identity();
    const Mat3 dashpot = c * n * n.transpose();
    g.stiffness += b.transpose() * spring * b;
    g.damping += b.transpose() * dashpot * b;
    g.sums.translation += spring;
    g.sums.rotation += lever.transpose() * spring * lever;
    const Vec3 w = r.cross(n);
    g.sums.translationDamping += dashpot;
    g.sums.rotationDamping += c * w * w.transpose();
}

/// The largest |eigenvalue| of one step of the simulation's scheme on @a g's linear equations
/// (half kick, drift, the force at the new position with the half step's velocity, half kick),
/// over the state (position, velocity, force): above 1, the step amplifies some motion.
double amplification(const LinearGrain& g, double dt)
{
    using Matrix = Eigen::Matrix<double, 18, 18>;
    using State = Eigen::Matrix<double, 18, 1>;
    const Eigen::Matrix<double, 6, 1> inverseMass = g.mass.cwiseInverse();
    Matrix step;
    for (int k = 0; k < 18; ++k) {
        const State s = State::Unit(k);
        const Eigen::Matrix<double, 6, 1> x = s.segment<6>(0), v = s.segment<6>(6),
                                          f = s.segment<6>(12);
        const Eigen::Matrix<double, 6, 1> half = v + 0.5 * dt * inverseMass.cwiseProduct(f);
        const Eigen::Matrix<double, 6, 1> moved = x + dt * half;
        const Eigen::Matrix<double, 6, 1> force = -g.stiffness * moved - g.damping * half;
        step.col(k) << moved, half + 0.5 * dt * inverseMass.cwiseProduct(force), force;
    }
    return Eigen::EigenSolver<Matrix>(step, false).eigenvalues().cwiseAbs().maxCoeff();
}

/// A body of mass @a m and principal moments @a inertia, at rest in its principal frame.
RigidBody principalBody(double m, const Vec3& inertia)
{
    RigidBody body;
    body.mass = m;
    body.principalInertia = inertia;
    return body;
}

} // namespace

// Dashpots pressing a grain in parallel add up as their springs do: a ball held between two
// walls, each contact a spring k and a dashpot at ratio β (c = 2β·sqrt(m·k)), has one mode of
// ω² = 2k/m damped at √2·β. The bound must see it: one step over it amplifies the motion (the
// scheme's own matrix says so), and the step one contact's ratio allows, 2/ω·(sqrt(1 + β²) −
// β), is 18 % too long at e = 0.2 (β = 0.456).
TEST(StableStep, ParallelDashpotsShortenTheStepAsTheSchemeFindsIt)
{
    const double m = 2.0, k = 50.0;
    const RigidBody ball = principalBody(m, Vec3::Constant(0.4 * m));
    for (const double beta : {0.1, 0.456, 1.0}) {
        LinearGrain g;
        g.mass << Vec3::Constant(m), ball.principalInertia;
        const double c = 2.0 * beta * std::sqrt(m * k);
        addContact(g, Vec3(0, 0, -1), Vec3::UnitZ(), k, 0.0, c);
        addContact(g, Vec3(0, 0, 1), -Vec3::UnitZ(), k, 0.0, c);
        const double limit = stableStep(g.sums, ball, beta);
        EXPECT_LE(amplification(g, 0.999 * limit), 1.0 + 1e-9) << beta;
        EXPECT_GT(amplification(g, 1.001 * limit), 1.0 + 1e-6) << beta;
        const double omega = std::sqrt(2.0 * k / m), b = std::sqrt(2.0) * beta;
        EXPECT_NEAR(limit, 2.0 / omega * (std::sqrt(1.0 + b * b) - b), 1e-12 * limit) << beta;
        // One contact's ratio alone (the check before 2026-11-30) lets through a step that
        // amplifies.
        GrainStiffness springsOnly = g.sums;
        springsOnly.translationDamping.setZero();
        springsOnly.rotationDamping.setZero();
        EXPECT_GT(amplification(g, 0.999 * stableStep(springsOnly, ball, beta)), 1.0 + 1e-6)
            << beta;
    }
}

// The bound holds for grains of any shape on any contacts: 1 to 6 contacts at random points
// and normals, springs in shear too, dashpots along the normals at ratio β for each one's
// normal stiffness (c = 2β·sqrt(m·k_n)); stableStep and its cheap bound never allow a step
// the scheme amplifies, though the springs' modes and the dashpots' differ here (the bound's
// premise, StableStep.h, is exact only where they are shared).
TEST(StableStep, NoStepWithinTheBoundAmplifiesAnyGrainsMotion)
{
    std::mt19937 random(11);
    std::normal_distribution<double> gaussian;
    std::uniform_real_distribution<double> uniform(0.1, 10.0), inertia(0.2, 5.0);
    int dashpotSetsTheStep = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const double m = inertia(random), beta = 0.25 * (trial % 5);
        const RigidBody body =
            principalBody(m, Vec3(inertia(random), inertia(random), inertia(random)));
        LinearGrain g;
        g.mass << Vec3::Constant(m), body.principalInertia;
        for (int c = 0; c < 1 + trial % 6; ++c) {
            const Vec3 n = Vec3(gaussian(random), gaussian(random), gaussian(random)).normalized();
            const Vec3 r(gaussian(random), gaussian(random), gaussian(random));
            const double kn = uniform(random), ks = trial % 2 ? 0.5 * uniform(random) : 0.0;
            addContact(g, r, n, kn, ks, 2.0 * beta * std::sqrt(m * kn));
        }
        const double limit = stableStep(g.sums, body, beta);
        // (Directions without stiffness drift freely: an eigenvalue 1 of a Jordan block, which
        // rounding moves by about √ε = 1.5e-8.)
        ASSERT_LE(amplification(g, 0.999 * limit), 1.0 + 1e-6) << "trial " << trial;
        ASSERT_LE(stableStepLowerBound(g.sums, body, beta), limit * (1.0 + 1e-12))
            << "trial " << trial;
        GrainStiffness springsOnly = g.sums;
        springsOnly.translationDamping.setZero();
        springsOnly.rotationDamping.setZero();
        if (stableStep(springsOnly, body, beta) > limit * (1.0 + 1e-9)) ++dashpotSetsTheStep;
    }
    // The summed dashpots, not each contact's ratio, set many of these steps.
    EXPECT_GT(dashpotSetsTheStep, 120);  // of the 240 with dashpots (234 here)
}
