#include "lsdem/simulation/RigidBody.h"

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
/// ω_k·t, so the body-frame momentum turns the other way; the world momentum is unchanged.
void rotateAboutPrincipalAxis(Quat& orientation, Vec3& bodyMomentum, const Vec3& inertia, int k,
                              double t)
{
    const double angle = bodyMomentum[k] / inertia[k] * t;
    const Eigen::AngleAxisd turn(angle, Vec3::Unit(k));
    orientation = (orientation * Quat(turn)).normalized();
    bodyMomentum = turn.inverse() * bodyMomentum;
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
    // World momentum is invariant under the free flow; recompute it from the body frame
    // only to keep orientation and momentum consistent after renormalisation.
    body.angularMomentum = q * bodyMomentum;
}

} // namespace lsdem
