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

/// The exact flow of T_k = L_k²/(2 I_k) for time @a t: the body turns about its axis k by
/// θ = ω_k·t, so the body-frame momentum turns by −θ; the world momentum is unchanged. One
/// sine and cosine of θ/2 serve both: the quaternion of the turn takes them as they are, the
/// momentum's rotation takes cos θ = 1 − 2 sin²(θ/2) and sin θ = 2 sin(θ/2) cos(θ/2).
void rotateAboutPrincipalAxis(Quat& orientation, Vec3& bodyMomentum, const Vec3& inertia, int k,
                              double t)
{
    const double half = 0.5 * bodyMomentum[k] / inertia[k] * t;
    const double s = std::sin(half), c = std::cos(half);
    Quat turn(c, 0.0, 0.0, 0.0);
    turn.vec()[k] = s;
    orientation = orientation * turn;
    const double cosine = 1.0 - 2.0 * s * s, sine = 2.0 * s * c;
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // (i, j, k) cyclic: turning by θ takes i to j
    const double li = bodyMomentum[i], lj = bodyMomentum[j];
    bodyMomentum[i] = cosine * li + sine * lj;
    bodyMomentum[j] = cosine * lj - sine * li;
}

} // namespace

void drift(RigidBody& body, double dt)
{
    body.pose.position += body.velocity * dt;
    Vec3 bodyMomentum = body.pose.orientation.conjugate() * body.angularMomentum;
    Quat& q = body.pose.orientation;
    const Vec3& inertia = body.principalInertia;
    rotateAboutPrincipalAxis(q, bodyMomentum, inertia, 0, 0.5 * dt);
    rotateAboutPrincipalAxis(q, bodyMomentum, inertia, 1, 0.5 * dt);
    rotateAboutPrincipalAxis(q, bodyMomentum, inertia, 2, dt);
    rotateAboutPrincipalAxis(q, bodyMomentum, inertia, 1, 0.5 * dt);
    rotateAboutPrincipalAxis(q, bodyMomentum, inertia, 0, 0.5 * dt);
    q.normalize();  // once per step: five exact turns leave it unit to round-off
    // World momentum is invariant under the free flow; recompute it from the body frame
    // only to keep orientation and momentum consistent after renormalisation.
    body.angularMomentum = q * bodyMomentum;
}

} // namespace lsdem
