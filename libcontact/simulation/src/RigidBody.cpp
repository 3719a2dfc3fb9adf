#include "lsdem/simulation/RigidBody.h"

#include <cmath>

namespace lsdem {

Vec3 RigidBody::angularVelocity() const
{
    const Vec3 bodyMomentum = pose.orientation.conjugate() * angularMomentum;
    return pose.orientation * bodyMomentum.cwiseQuotient(principalInertia);
}

void RigidBody::setAngularVelocity(const Vec3& omega)
{
    const Vec3 bodyOmega = pose.orientation.conjugate() * omega;
    angularMomentum = pose.orientation * bodyOmega.cwiseProduct(principalInertia);
}

double RigidBody::kineticEnergy() const
{
    const Vec3 bodyMomentum = pose.orientation.conjugate() * angularMomentum;
    return 0.5 * mass * velocity.squaredNorm() +
           0.5 * bodyMomentum.cwiseProduct(bodyMomentum).cwiseQuotient(principalInertia).sum();
}

void kick(RigidBody& body, const Vec3& force, const Vec3& torque, double halfStep)
{
    body.velocity += force * (halfStep / body.mass);
    body.angularMomentum += torque * halfStep;
}

namespace {

/// sin x and cos x. A grain turns by far less than a milliradian per step, where the Taylor
/// series through x⁵ and x⁴ are exact to round-off (the first terms left out, x⁷/5040 and
/// x⁶/720, are below 2e-21 of the result for |x| ≤ 1e-3) and several times cheaper than the
/// library's sincos.
void sineAndCosine(double x, double& sine, double& cosine)
{
    if (std::abs(x) > 1e-3) {
        sine = std::sin(x);
        cosine = std::cos(x);
        return;
    }
    constexpr double kSixth = 1.0 / 6.0, kTwentieth = 1.0 / 20.0, kTwelfth = 1.0 / 12.0;
    const double x2 = x * x;
    sine = x * (1.0 - x2 * kSixth * (1.0 - x2 * kTwentieth));
    cosine = 1.0 - 0.5 * x2 * (1.0 - x2 * kTwelfth);
}

/// A free rigid rotation in the body frame, held as plain numbers so that the five turns of a
/// step stay in registers: the orientation (w, x, y, z) and the body-frame momentum.
struct BodyRotation
{
    double q[4];
    double momentum[3];
};

/// The exact flow of T_k = L_k²/(2 I_k) for time @a t: the body turns about its axis K by
/// θ = ω_K·t, so the body-frame momentum turns by −θ; the world momentum is unchanged. One
/// sine and cosine of θ/2 serve both: the quaternion of the turn, (cos θ/2, sin θ/2·e_K),
/// takes them as they are, the momentum's rotation takes cos θ = 1 − 2 sin²(θ/2) and
/// sin θ = 2 sin(θ/2) cos(θ/2). The axis is a template argument, so every index is fixed.
template <int K>
void turnAboutPrincipalAxis(BodyRotation& r, const Vec3& inertia, double t)
{
    constexpr int I = (K + 1) % 3, J = (K + 2) % 3;  // (I, J, K) cyclic
    const double half = 0.5 * r.momentum[K] / inertia[K] * t;
    double s = 0.0, c = 1.0;
    sineAndCosine(half, s, c);
    // q ← q ⊗ (c, s·e_K), written out: the vector part of q is (q[1], q[2], q[3]).
    const double w = r.q[0], vi = r.q[1 + I], vj = r.q[1 + J], vk = r.q[1 + K];
    r.q[0] = c * w - s * vk;
    r.q[1 + I] = c * vi + s * vj;
    r.q[1 + J] = c * vj - s * vi;
    r.q[1 + K] = c * vk + s * w;
    const double cosine = 1.0 - 2.0 * s * s, sine = 2.0 * s * c;
    const double li = r.momentum[I], lj = r.momentum[J];
    r.momentum[I] = cosine * li + sine * lj;
    r.momentum[J] = cosine * lj - sine * li;
}

} // namespace

void drift(RigidBody& body, double dt)
{
    body.pose.position += body.velocity * dt;
    Quat& q = body.pose.orientation;
    const Vec3 bodyMomentum = q.conjugate() * body.angularMomentum;
    BodyRotation r{{q.w(), q.x(), q.y(), q.z()},
                   {bodyMomentum.x(), bodyMomentum.y(), bodyMomentum.z()}};
    const Vec3& inertia = body.principalInertia;
    turnAboutPrincipalAxis<0>(r, inertia, 0.5 * dt);
    turnAboutPrincipalAxis<1>(r, inertia, 0.5 * dt);
    turnAboutPrincipalAxis<2>(r, inertia, dt);
    turnAboutPrincipalAxis<1>(r, inertia, 0.5 * dt);
    turnAboutPrincipalAxis<0>(r, inertia, 0.5 * dt);
    q = Quat(r.q[0], r.q[1], r.q[2], r.q[3]);
    q.normalize();  // once per step: five exact turns leave it unit to round-off
    // World momentum is invariant under the free flow; recompute it from the body frame
    // only to keep orientation and momentum consistent after renormalisation.
    body.angularMomentum = q * Vec3(r.momentum[0], r.momentum[1], r.momentum[2]);
}

} // namespace lsdem
