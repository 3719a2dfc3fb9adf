/// @file ShearFieldReference.h
/// @brief A ball's impact on a rigid surface under a per-node law, computed point by point
///        from the law's definition: the reference of the verification suite's oblique impacts
///        and impacts with spin (Chung & Ooi tests 4–6 and 8), where the slip may stop during
///        the contact and rigid-body theory then cannot give the outcome, since the tangential
///        springs decide it.
///
/// The ball is a set of surface points, each with its tributary area: either its own nodes
/// (the law as lsdem applies it to this node set) or a fine lattice of its surface around the
/// contact (the law's continuum limit). Each point below the surface is depth d deep and
/// pushes with its spring along the surface's normal; its shear spring starts from zero when it
/// enters, takes −k_t·(slip)·dt, turns with the ball's spin about the normal, is capped at μ
/// times its normal force (spring and share of the dashpot) and is dropped when it leaves; its
/// forces act halfway between it and the surface. The contact's dashpot acts at the springs'
/// stiffness-weighted centre, along the surface's normal there, with the ratio for the
/// contact's exponent, pushing but not pulling. The ball moves as a rigid body (semi-implicit
/// Euler at a twentieth of a thousandth of the contact); the surface does not move. A second
/// implementation of the law's definition for this one geometry: no level set, no narrow
/// phase, no contact list, none of lsdem's contact or simulation code.
#pragma once

#include "studies/verify/VerifySetup.h"

#include <vector>

namespace lsdem::verify {

/// Points of a ball's surface, in its own frame (centre at the origin), with their areas.
struct SurfacePoints
{
    std::vector<Vec3> positions;
    std::vector<double> areas;
};

/// The ball's own nodes.
SurfacePoints nodesOf(const GrainAsset& ball);

/// A lattice of a sphere of radius @a radius within @a angle of its lowest point (rings about
/// −z, points @a spacing apart, each with its ring's share of the exact zone area).
SurfacePoints lowerCap(double radius, double angle, double spacing);

/// The rigid surface: the plane z = 0 (normal +z), or a sphere of radius @a radius whose top is
/// at the origin (the ball meets it from above).
struct Surface
{
    double radius = 0.0;  ///< 0: the plane
    double depthOf(const Vec3& p) const;  ///< > 0 inside
    Vec3 normalAt(const Vec3& p) const;   ///< unit, outward
};

struct BallImpact
{
    Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();  ///< after the impact
    double maxOverlap = 0.0;
};

/// The ball (@a points, mass @a mass, inertia @a inertia about any axis) coming down onto
/// @a surface with velocity @a velocity and spin @a spin, its centre @a height above the
/// surface's top; @a law's stiffness rules and coefficients; steps of @a step.
BallImpact ballOnSurface(const SurfacePoints& points, const ContactModel& law, double mass,
                         double inertia, const Surface& surface, double height,
                         const Vec3& velocity, const Vec3& spin, double step);

} // namespace lsdem::verify
