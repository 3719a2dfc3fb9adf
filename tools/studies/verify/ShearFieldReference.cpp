#include "studies/verify/ShearFieldReference.h"

#include "lsdem/core/Constants.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

SurfacePoints nodesOf(const GrainAsset& ball)
{
    return {ball.nodes.positions, ball.nodes.areas};
}

SurfacePoints lowerCap(double radius, double angle, double spacing)
{
    SurfacePoints out;
    const int rings = std::max(1, int(std::ceil(radius * angle / spacing)));
    const double dTheta = angle / rings;
    for (int i = 0; i < rings; ++i) {
        const double low = i * dTheta, high = (i + 1) * dTheta, theta = 0.5 * (low + high);
        const double zone = 2.0 * kPi * radius * radius * (std::cos(low) - std::cos(high));
        const int count = std::max(1, int(std::round(2.0 * kPi * radius * std::sin(theta) / spacing)));
        for (int k = 0; k < count; ++k) {
            const double around = 2.0 * kPi * (k + 0.5 * (i % 2)) / count;
            out.positions.push_back(radius * Vec3(std::sin(theta) * std::cos(around),
                                                  std::sin(theta) * std::sin(around),
                                                  -std::cos(theta)));
            out.areas.push_back(zone / count);
        }
    }
    return out;
}

double Surface::depthOf(const Vec3& p) const
{
    if (radius <= 0.0) return -p.z();
    return radius - (p - Vec3(0, 0, -radius)).norm();
}

Vec3 Surface::normalAt(const Vec3& p) const
{
    if (radius <= 0.0) return Vec3::UnitZ();
    return (p - Vec3(0, 0, -radius)).normalized();
}

// The reference integrator, written apart from lsdem's contact code so that it can be read
// against the equations (ShearFieldReference.h): one function per step of the law, in the
// order a time step takes them.
namespace {

/// The ball as it moves: its centre, velocity, spin and turn from its start.
struct BallState
{
    Vec3 centre, v, w;
    Quat turn;
};

/// Each point's normal and shear spring stiffness: the law's, times the point's area for a
/// law per area.
struct PointStiffness
{
    std::vector<double> normal, shear;
};

PointStiffness pointStiffness(const SurfacePoints& points, const ContactModel& law)
{
    const bool perArea = law.normal().stiffnessPerArea();
    const size_t n = points.positions.size();
    PointStiffness k{std::vector<double>(n), std::vector<double>(n)};
    for (size_t a = 0; a < n; ++a) {
        k.normal[a] = perArea ? law.normalStiffness * points.areas[a] : law.normalStiffness;
        k.shear[a] = perArea ? law.shearStiffness * points.areas[a] : law.shearStiffness;
    }
    return k;
}

/// The contact as a whole, summed over the points below the surface (for the dashpot).
struct ContactSums
{
    double total = 0.0, elastic = 0.0, deepest = 0.0, areas = 0.0, squares = 0.0;
    Vec3 weighted = Vec3::Zero();
    bool any = false;
};

/// Every point placed in the world (@a world) with its depth below the surface (@a depth);
/// the sums of those below it.
ContactSums placePoints(const SurfacePoints& points, const std::vector<double>& normalStiffness,
                        const Surface& surface, const BallState& ball, std::vector<Vec3>& world,
                        std::vector<double>& depth)
{
    ContactSums sums;
    for (size_t a = 0; a < world.size(); ++a) {
        world[a] = ball.centre + ball.turn * points.positions[a];
        depth[a] = surface.depthOf(world[a]);
        if (depth[a] <= 0.0) continue;
        sums.any = true;
        sums.total += normalStiffness[a];
        sums.elastic += normalStiffness[a] * depth[a];
        sums.weighted += normalStiffness[a] * world[a];
        sums.deepest = std::max(sums.deepest, depth[a]);
        sums.areas += points.areas[a];
        sums.squares += points.areas[a] * points.areas[a];
    }
    return sums;
}

/// The contact's dashpot force and torque on the ball, added to @a force and @a torque: at the
/// springs' stiffness-weighted centre, along the surface's normal there, pushing but not
/// pulling. Returns its normal force over Σ k·d: each point's friction limit takes a share in
/// proportion to its spring's force.
double addDashpot(const ContactModel& law, double mass, const Surface& surface,
                  const ContactSums& sums, const BallState& ball, Vec3& force, Vec3& torque)
{
    const Vec3 at = sums.weighted / sums.total;
    const Vec3 normal = surface.normalAt(at);
    // (On a plane every point's normal is the contact's; on a heavy ball the tilt
    // within the cap is second order.)
    const double exponent = std::max(
        1.0, sums.deepest * (1.0 + sums.squares / (sums.areas * sums.areas)) * sums.total /
                 sums.elastic);
    const double dashpot = law.damping.dashpot(
        mass, sums.total, law.normal().perNodeForces() ? exponent : 1.0);
    const double separating = (ball.v + ball.w.cross(at - ball.centre)).dot(normal);
    const double viscous = std::max(-dashpot * separating, -sums.elastic);
    force += viscous * normal;
    torque += (at - ball.centre).cross(viscous * normal);
    return viscous / sums.elastic;
}

/// A point's shear spring @a stored carried through the step at @a point (normal @a normal):
/// kept in the tangent plane at its size, turned with the ball's spin about the normal, less
/// k_t times the slip, and capped at @a limit.
Vec3 shearSpring(const Vec3& stored, const Vec3& normal, const Vec3& point, const BallState& ball,
                 double shearStiffness, double limit, double step)
{
    const Vec3 slip = (ball.v + ball.w.cross(point - ball.centre)) * step;
    Vec3 s = stored - stored.dot(normal) * normal;
    s += (0.5 * ball.w.dot(normal) * step) * normal.cross(s);
    if (s.squaredNorm() > 0.0) s *= stored.norm() / s.norm();
    s -= shearStiffness * (slip - slip.dot(normal) * normal);
    if (s.norm() > limit) s *= limit > 0.0 ? limit / s.norm() : 0.0;
    return s;
}

/// Semi-implicit Euler: the velocities with these forces, then the positions.
void advance(BallState& ball, const Vec3& force, const Vec3& torque, double mass, double inertia,
             double step)
{
    ball.v += force / mass * step;
    ball.w += torque / inertia * step;
    ball.centre += ball.v * step;
    const double angle = ball.w.norm() * step;
    if (angle > 0.0)
        ball.turn = (Quat(Eigen::AngleAxisd(angle, ball.w.normalized())) * ball.turn).normalized();
}

} // namespace

BallImpact ballOnSurface(const SurfacePoints& points, const ContactModel& law, double mass,
                         double inertia, const Surface& surface, double height,
                         const Vec3& velocity, const Vec3& spin, double step)
{
    const bool shear = law.tangential().active(law.normal());
    const size_t n = points.positions.size();
    const PointStiffness stiffness = pointStiffness(points, law);
    std::vector<Vec3> stored(n, Vec3::Zero());
    BallState ball{Vec3(0, 0, height), velocity, spin, Quat::Identity()};
    BallImpact out;
    bool touched = false;
    std::vector<Vec3> world(n);
    std::vector<double> depth(n);
    for (long k = 0; k < 50000000L; ++k) {
        const ContactSums sums = placePoints(points, stiffness.normal, surface, ball, world, depth);
        touched = touched || sums.any;
        if (touched && !sums.any) break;
        Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
        double viscousPerForce = 0.0;
        if (sums.any && law.damping.active())
            viscousPerForce = addDashpot(law, mass, surface, sums, ball, force, torque);
        // Each point's spring, and its shear spring (which starts from zero when it enters and
        // is dropped when it leaves); its forces act halfway between it and the surface.
        for (size_t a = 0; a < n; ++a) {
            if (depth[a] <= 0.0) {
                stored[a] = Vec3::Zero();
                continue;
            }
            const Vec3 normal = surface.normalAt(world[a]);
            const Vec3 point = world[a] + 0.5 * depth[a] * normal;
            Vec3 f = stiffness.normal[a] * depth[a] * normal;
            if (shear) {
                const double normalForce =
                    stiffness.normal[a] * depth[a] * (1.0 + viscousPerForce);
                const double limit = law.friction * std::max(0.0, normalForce);
                stored[a] =
                    shearSpring(stored[a], normal, point, ball, stiffness.shear[a], limit, step);
                f += stored[a];
            }
            force += f;
            torque += (point - ball.centre).cross(f);
        }
        advance(ball, force, torque, mass, inertia, step);
        out.maxOverlap = std::max(out.maxOverlap, sums.deepest);
    }
    out.velocity = ball.v;
    out.angularVelocity = ball.w;
    return out;
}

} // namespace lsdem::verify
