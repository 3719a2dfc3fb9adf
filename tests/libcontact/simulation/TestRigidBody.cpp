// Rigid-body stepping: conservation laws of the free rigid body and Newton's second law.
#include "lsdem/simulation/RigidBody.h"

#include <gtest/gtest.h>

using namespace lsdem;

namespace {

/// A free asymmetric body spun about an axis near its intermediate principal axis, the
/// unstable one (the "tennis racket" flip), so the orientation changes a lot in the run.
RigidBody tumblingBody()
{
    RigidBody b;
    b.mass = 2.0;
    b.principalInertia = Vec3(1.0, 2.0, 3.0);
    b.pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));
    b.setAngularVelocity(b.pose.orientation * Vec3(0.01, 5.0, 0.02));
    b.velocity = Vec3(0.3, -0.1, 0.2);
    return b;
}

void run(RigidBody& b, double dt, int steps)
{
    for (int i = 0; i < steps; ++i) {
        kick(b, Vec3::Zero(), Vec3::Zero(), 0.5 * dt);
        drift(b, dt);
        kick(b, Vec3::Zero(), Vec3::Zero(), 0.5 * dt);
    }
}

} // namespace

TEST(RigidBody, FreeTumblingKeepsMomentumAndEnergy)
{
    RigidBody b = tumblingBody();
    const Vec3 momentum = b.angularMomentum;
    const double energy = b.kineticEnergy();
    const Vec3 start = b.pose.position;
    const Vec3 bodyAxisBefore = b.pose.orientation * Vec3::UnitY();
    const double dt = 1e-3;
    run(b, dt, 20000);  // 20 time units: several flips at ω ≈ 5
    // World angular momentum: each split rotation keeps it exactly, so only round-off remains.
    EXPECT_NEAR((b.angularMomentum - momentum).norm(), 0.0, 1e-10 * momentum.norm());
    // Energy: a symplectic second-order method keeps it within O((ω dt)²) = 2.5e-5.
    EXPECT_NEAR(b.kineticEnergy() / energy, 1.0, 2.5e-5);
    // The body did tumble (the intermediate axis flipped away from where it started) ...
    EXPECT_LT((b.pose.orientation * Vec3::UnitY()).dot(bodyAxisBefore), 0.9);
    // ... and the centroid moved uniformly.
    EXPECT_NEAR((b.pose.position - (start + 20.0 * b.velocity)).norm(), 0.0, 1e-9);
    EXPECT_NEAR(b.pose.orientation.norm(), 1.0, 1e-12);
}

TEST(RigidBody, EnergyErrorIsSecondOrderInTheStep)
{
    // Halving dt cuts the largest energy deviation over the same time about four times.
    auto worstDeviation = [](double dt) {
        RigidBody b = tumblingBody();
        const double energy = b.kineticEnergy();
        double worst = 0.0;
        for (int i = 0; i < int(4.0 / dt); ++i) {
            run(b, dt, 1);
            worst = std::max(worst, std::abs(b.kineticEnergy() / energy - 1.0));
        }
        return worst;
    };
    const double coarse = worstDeviation(4e-3), fine = worstDeviation(2e-3);
    EXPECT_GT(coarse, 0.0);
    EXPECT_NEAR(coarse / fine, 4.0, 0.6);
}

TEST(RigidBody, ConstantForceAndTorqueGiveTheExpectedMotion)
{
    RigidBody b;
    b.mass = 3.0;
    b.principalInertia = Vec3(2.0, 2.0, 2.0);  // isotropic: ω = L / I in any frame
    const Vec3 force(0, 0, -6.0), torque(0, 0, 1.0);
    const double dt = 1e-3;
    for (int i = 0; i < 1000; ++i) {
        kick(b, force, torque, 0.5 * dt);
        drift(b, dt);
        kick(b, force, torque, 0.5 * dt);
    }
    // After t = 1: v = F t / m, x = F t² / (2m) exactly for velocity Verlet; ω = τ t / I.
    EXPECT_NEAR(b.velocity.z(), -2.0, 1e-12);
    EXPECT_NEAR(b.pose.position.z(), -1.0, 1e-12);
    EXPECT_NEAR(b.angularVelocity().z(), 0.5, 1e-12);
    // Angle turned: ∫ ω dt = τ t² / (2I) = 0.25 rad about z.
    EXPECT_NEAR(Eigen::AngleAxisd(b.pose.orientation).angle(), 0.25, 1e-6);
}

TEST(RigidBody, SpinAboutAPrincipalAxisTurnsByExactlyOmegaDt)
{
    // Spinning about a principal axis is a stationary free rotation: one step turns the body
    // by ω·dt about it, with nothing else to split. The step's sine and cosine come from a
    // series below 1e-3 rad and from the library above: both must give the exact rotation to
    // round-off, on either side of the switch and far from it.
    for (const double halfAngle : {1e-7, 3e-4, 0.999e-3, 1.001e-3, 0.05, 0.7}) {
        RigidBody b;
        b.mass = 1.0;
        b.principalInertia = Vec3(1.0, 2.0, 3.0);
        const double omega = 4.0, dt = 2.0 * halfAngle / omega;
        b.setAngularVelocity(Vec3(0.0, 0.0, omega));
        drift(b, dt);
        const Quat exact(std::cos(halfAngle), 0.0, 0.0, std::sin(halfAngle));
        EXPECT_NEAR((b.pose.orientation.coeffs() - exact.coeffs()).norm(), 0.0, 4e-16)
            << "half-angle " << halfAngle;
        EXPECT_NEAR((b.angularMomentum - Vec3(0.0, 0.0, 3.0 * omega)).norm(), 0.0, 1e-15);
    }
}

// The kinetic energy itself, not only its conservation (a constant factor on the rotational
// part would keep every ratio): ½mv² + ½ωᵀ(R·diag(I)·Rᵀ)ω, written out independently here for
// a body turned away from its principal axes.
TEST(RigidBody, KineticEnergyIsHalfMvSquaredPlusHalfOmegaIOmega)
{
    RigidBody b = tumblingBody();
    const Vec3 omega(0.7, -1.3, 2.1);
    b.setAngularVelocity(omega);
    const Mat3 R = b.pose.orientation.toRotationMatrix();
    const Mat3 inertia = R * b.principalInertia.asDiagonal() * R.transpose();
    const double expected = 0.5 * b.mass * b.velocity.dot(b.velocity) +
                            0.5 * omega.dot(inertia * omega);
    EXPECT_NEAR(b.kineticEnergy(), expected, 1e-13 * expected);
    EXPECT_NEAR((b.angularVelocity() - omega).norm(), 0.0, 1e-14);
}

// A world torque changes the world angular momentum by τ·t whatever the body's shape and
// orientation (the drift keeps world L to round-off): a torque taken in the body frame would
// pass an isotropic body at the identity, so this body is neither.
TEST(RigidBody, WorldTorqueAddsToTheWorldAngularMomentum)
{
    RigidBody b = tumblingBody();
    const Vec3 start = b.angularMomentum, torque(0.3, -0.2, 0.5);
    const double dt = 1e-3;
    const int steps = 500;
    for (int i = 0; i < steps; ++i) {
        kick(b, Vec3::Zero(), torque, 0.5 * dt);
        drift(b, dt);
        kick(b, Vec3::Zero(), torque, 0.5 * dt);
    }
    const Vec3 expected = start + torque * (dt * steps);
    EXPECT_NEAR((b.angularMomentum - expected).norm(), 0.0, 1e-12 * expected.norm());
}
