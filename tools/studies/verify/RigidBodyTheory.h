/// @file RigidBodyTheory.h
/// @brief Rigid-body theory of the verification suite's frictional cases, derived from
///        impulse and momentum (no contact law in it): the oblique impact of spheres with
///        Coulomb friction (Chung & Ooi tests 4–8: gross sliding when the slip cannot be
///        stopped by μ times the normal impulse, otherwise the slip stops), the slide to roll
///        of a ball thrown onto a floor, and a block sliding down an incline.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem::verify {

/// A rigid sphere at an impact: its velocities, and the lever from its centre to the contact
/// point. A wall is a body of infinite mass (movable = false).
struct ImpactBody
{
    double mass = 0.0, inertia = 0.0;  ///< inertia about any axis (a sphere's)
    Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
    Vec3 lever = Vec3::Zero();  ///< centre to contact point, parallel to the normal
    bool movable = true;
};

struct ImpactOutcome
{
    ImpactBody first, second;  ///< after the impact
    bool slides = false;       ///< gross sliding throughout (else the slip stops)
    Vec3 slipBefore = Vec3::Zero(), slipAfter = Vec3::Zero();  ///< tangential, contact point
};

/// The impact of @a first on @a second along @a normal (unit, pushing @a first away from
/// @a second) with restitution @a restitution and friction @a friction: normal impulse
/// J_n = (1 + e)·m*·V_n; the tangential impulse that would stop the slip s,
/// J = s/(1/m₁ + 1/m₂ + R₁²/I₁ + R₂²/I₂), if μ·J_n can give it (sticking), else μ·J_n against
/// the slip (gross sliding). For two solid spheres or a sphere on a wall this slides iff
/// |s|/V_n ≥ 3.5·μ·(1 + e).
ImpactOutcome rigidImpact(const ImpactBody& first, const ImpactBody& second, const Vec3& normal,
                          double restitution, double friction);

/// A solid ball thrown flat onto a floor at speed @a speed without spin slides while friction
/// μ·g decelerates it and spins it up; the slip ends at t = 2v₀/(7μg), where it rolls on at
/// 5/7·v₀ for ever.
struct SlideToRoll
{
    double slipTime = 0.0, rollingSpeed = 0.0;
};
SlideToRoll slideToRoll(double speed, double friction, double gravity);

/// The acceleration of a block sliding down an incline at @a angle (radians) with friction
/// @a friction under gravity @a gravity: g·(sin θ − μ·cos θ), or 0 where it sticks.
double inclineAcceleration(double angle, double friction, double gravity);

} // namespace lsdem::verify
