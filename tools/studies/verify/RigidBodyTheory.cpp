#include "studies/verify/RigidBodyTheory.h"

#include <Eigen/Geometry>

#include <cmath>

namespace lsdem::verify {

namespace {

/// What one unit of impulse along a tangent changes the slip by, for one body.
double tangentialCompliance(const ImpactBody& b)
{
    return b.movable ? 1.0 / b.mass + b.lever.squaredNorm() / b.inertia : 0.0;
}

Vec3 contactPointVelocity(const ImpactBody& b)
{
    return b.velocity + b.angularVelocity.cross(b.lever);
}

void applyImpulse(ImpactBody& b, const Vec3& impulse)
{
    if (!b.movable) return;
    b.velocity += impulse / b.mass;
    b.angularVelocity += b.lever.cross(impulse) / b.inertia;
}

} // namespace

ImpactOutcome rigidImpact(const ImpactBody& first, const ImpactBody& second, const Vec3& normal,
                          double restitution, double friction)
{
    ImpactOutcome out;
    out.first = first;
    out.second = second;
    const Vec3 relative = contactPointVelocity(first) - contactPointVelocity(second);
    const double approach = -relative.dot(normal);  // V_n > 0 when closing
    const double inverseMass =
        (first.movable ? 1.0 / first.mass : 0.0) + (second.movable ? 1.0 / second.mass : 0.0);
    const double normalImpulse = (1.0 + restitution) * approach / inverseMass;
    out.slipBefore = relative - relative.dot(normal) * normal;
    const double slip = out.slipBefore.norm();
    const double compliance = tangentialCompliance(first) + tangentialCompliance(second);
    const double stopping = slip / compliance;
    out.slides = stopping > friction * normalImpulse;
    const double tangential = out.slides ? friction * normalImpulse : stopping;
    Vec3 impulse = normalImpulse * normal;
    if (slip > 0.0) impulse -= tangential * out.slipBefore / slip;
    applyImpulse(out.first, impulse);
    applyImpulse(out.second, -impulse);
    const Vec3 after = contactPointVelocity(out.first) - contactPointVelocity(out.second);
    out.slipAfter = after - after.dot(normal) * normal;
    return out;
}

SlideToRoll slideToRoll(double speed, double friction, double gravity)
{
    // Slip s = v − R·ω falls at μg (deceleration) + R·(5μg/(2R)) (spin-up) = 3.5·μ·g.
    SlideToRoll r;
    r.slipTime = speed / (3.5 * friction * gravity);
    r.rollingSpeed = speed - friction * gravity * r.slipTime;
    return r;
}

double inclineAcceleration(double angle, double friction, double gravity)
{
    const double driving = std::sin(angle) - friction * std::cos(angle);
    return driving > 0.0 ? gravity * driving : 0.0;
}

} // namespace lsdem::verify
