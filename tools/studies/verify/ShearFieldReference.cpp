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

// Long on purpose: the whole reference integrator in one place, written apart from lsdem's
// contact code, so that it can be read against the equations line by line.
BallImpact ballOnSurface(const SurfacePoints& points, const ContactModel& law, double mass,
                         double inertia, const Surface& surface, double height,
                         const Vec3& velocity, const Vec3& spin, double step)
{
    const NormalModel& normalLaw = law.normal();
    const bool perArea = normalLaw.stiffnessPerArea();
    const bool shear = law.tangential().active(normalLaw);
    const size_t n = points.positions.size();
    std::vector<double> normalStiffness(n), shearStiffness(n);
    for (size_t a = 0; a < n; ++a) {
        normalStiffness[a] = perArea ? law.normalStiffness * points.areas[a] : law.normalStiffness;
        shearStiffness[a] = perArea ? law.shearStiffness * points.areas[a] : law.shearStiffness;
    }
    std::vector<Vec3> stored(n, Vec3::Zero());
    std::vector<bool> inside(n, false);
    Vec3 centre(0, 0, height), v = velocity, w = spin;
    Quat turn = Quat::Identity();
    BallImpact out;
    bool touched = false;
    std::vector<Vec3> world(n);
    std::vector<double> depth(n);
    for (long k = 0; k < 50000000L; ++k) {
        // The points below the surface, and the contact as a whole (for the dashpot).
        double total = 0.0, elastic = 0.0, deepest = 0.0, areas = 0.0, squares = 0.0;
        Vec3 weighted = Vec3::Zero();
        bool any = false;
        for (size_t a = 0; a < n; ++a) {
            world[a] = centre + turn * points.positions[a];
            depth[a] = surface.depthOf(world[a]);
            if (depth[a] <= 0.0) continue;
            any = true;
            total += normalStiffness[a];
            elastic += normalStiffness[a] * depth[a];
            weighted += normalStiffness[a] * world[a];
            deepest = std::max(deepest, depth[a]);
            areas += points.areas[a];
            squares += points.areas[a] * points.areas[a];
        }
        touched = touched || any;
        if (touched && !any) break;
        Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
        double viscousPerStiffness = 0.0;
        if (any && law.damping.active()) {
            const Vec3 at = weighted / total;
            const Vec3 normal = surface.normalAt(at);
            // (On a plane every point's normal is the contact's; on a heavy ball the tilt
            // within the cap is second order.)
            const double exponent =
                std::max(1.0, deepest * (1.0 + squares / (areas * areas)) * total / elastic);
            const double dashpot =
                law.damping.dashpot(mass, total, normalLaw.perNodeForces() ? exponent : 1.0);
            const double separating = (v + w.cross(at - centre)).dot(normal);
            const double viscous = std::max(-dashpot * separating, -elastic);
            viscousPerStiffness = viscous / total;
            force += viscous * normal;
            torque += (at - centre).cross(viscous * normal);
        }
        for (size_t a = 0; a < n; ++a) {
            if (depth[a] <= 0.0) {
                stored[a] = Vec3::Zero();
                continue;
            }
            const Vec3 normal = surface.normalAt(world[a]);
            const Vec3 point = world[a] + 0.5 * depth[a] * normal;
            Vec3 f = normalStiffness[a] * depth[a] * normal;
            if (shear) {
                const Vec3 slip = (v + w.cross(point - centre)) * step;
                Vec3 s = stored[a] - stored[a].dot(normal) * normal;
                s += (0.5 * w.dot(normal) * step) * normal.cross(s);
                if (s.squaredNorm() > 0.0) s *= stored[a].norm() / s.norm();
                s -= shearStiffness[a] * (slip - slip.dot(normal) * normal);
                const double limit =
                    law.friction * std::max(0.0, normalStiffness[a] * (depth[a] + viscousPerStiffness));
                if (s.norm() > limit) s *= limit > 0.0 ? limit / s.norm() : 0.0;
                stored[a] = s;
                f += s;
            }
            force += f;
            torque += (point - centre).cross(f);
        }
        // Semi-implicit Euler: the velocities with these forces, then the positions.
        v += force / mass * step;
        w += torque / inertia * step;
        centre += v * step;
        const double angle = w.norm() * step;
        if (angle > 0.0) turn = (Quat(Eigen::AngleAxisd(angle, w.normalized())) * turn).normalized();
        out.maxOverlap = std::max(out.maxOverlap, deepest);
    }
    out.velocity = v;
    out.angularVelocity = w;
    return out;
}

} // namespace lsdem::verify
