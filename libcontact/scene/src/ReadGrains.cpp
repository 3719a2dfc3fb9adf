// [[grains]] and [[lattices]]: grains one by one or in blocks, with their orientation and
// motion.
#include "SceneSections.h"

#include "lsdem/scene/EntryRules.h"

#include "lsdem/core/Constants.h"
#include "lsdem/scene/RandomRotation.h"

#include <random>

namespace lsdem::scenefile {

Quat readOrientation(TableReader& t)
{
    if (t.has("orientation") && t.has("axis_angle"))
        t.fail("axis_angle", "both orientation and axis_angle are given", "keep one of them");
    if (t.has("orientation")) {
        const std::vector<double> q = t.numbers("orientation", 4);
        const Quat r(q[0], q[1], q[2], q[3]);
        if (std::optional<std::string> p = orientationProblem(r))
            t.fail("orientation", *p,
                   std::string(kOrientationFix) + ", or use axis_angle = [ax, ay, az, degrees]");
        return unitQuaternion(r);
    }
    if (t.has("axis_angle")) {
        const std::vector<double> v = t.numbers("axis_angle", 4);
        const Vec3 axis(v[0], v[1], v[2]);
        if (!(axis.norm() > 0.0))
            t.fail("axis_angle", "has a zero axis", "give a direction, e.g. [0, 0, 1, 30]");
        return Quat(Eigen::AngleAxisd(v[3] * kPi / 180.0, axis.normalized()));
    }
    return Quat::Identity();
}

/// The motion and velocities of a grain (or of every grain of a lattice).
void readMotion(TableReader& t, GrainSpec& g)
{
    g.motion = *parseGrainMotion(
        t.choice("motion", grainMotionNames(), grainMotionName(GrainMotion::Free)));
    g.velocity = t.vec3("velocity", Vec3::Zero());
    g.angularVelocity = t.vec3("angular_velocity", Vec3::Zero());
    if (g.motion == GrainMotion::Fixed && (t.has("velocity") || t.has("angular_velocity")))
        t.fail(t.has("velocity") ? "velocity" : "angular_velocity",
               "a fixed grain cannot move",
               "remove the velocity, or write motion = \"prescribed\" to move it at that velocity");
    if (t.has("mass")) g.mass = t.positive("mass");
}

GrainSpec readGrain(TableReader& t, const Scene& scene)
{
    GrainSpec g;
    g.where = t.where();
    g.name = t.string("name", "");
    g.asset = lookUpAsset(t, scene);
    g.material = lookUpMaterial(t, scene);
    g.pose.position = t.vec3("position");
    g.pose.orientation = readOrientation(t);
    readMotion(t, g);
    t.rejectUnknownKeys();
    return g;
}

/// A block of count[0]×count[1]×count[2] grains at origin + (i, j, k)·spacing, optionally
/// jittered and randomly turned (seeded, reproducible everywhere).
void readLattice(TableReader& t, Scene& scene)
{
    GrainSpec model;
    model.where = t.where();
    const std::string prefix = t.string("name", "");
    model.asset = lookUpAsset(t, scene);
    model.material = lookUpMaterial(t, scene);
    const Vec3 origin = t.vec3("origin");
    const std::vector<double> c = t.numbers("count", 3);
    long long count[3];
    for (int d = 0; d < 3; ++d) {
        if (!(c[d] >= 1.0 && c[d] == std::floor(c[d]) && c[d] <= 1e6))
            t.fail("count", "must hold three positive integers", "write e.g. count = [3, 3, 3]");
        count[d] = static_cast<long long>(c[d]);
    }
    // Checked before any grain is made: a short file must not fill the memory.
    const long long wanted = count[0] * count[1] * count[2];
    const long long before = static_cast<long long>(scene.grains.size());
    if (wanted > kMaxSceneGrains - before)
        t.fail("count",
               "asks for " + std::to_string(wanted) + " grains, which would bring the scene to " +
                   std::to_string(before + wanted) + ", over the limit of " +
                   std::to_string(kMaxSceneGrains),
               "use a smaller lattice");
    const Vec3 spacing = t.vec3("spacing");
    for (int d = 0; d < 3; ++d)
        if (count[d] > 1 && !(spacing[d] > 0.0))
            t.fail("spacing", "must be > 0 along every axis with more than one grain", "");
    const double jitter = t.nonNegative("jitter", 0.0);
    const bool randomOrientation = t.boolean("random_orientation", false);
    if (randomOrientation && (t.has("orientation") || t.has("axis_angle")))
        t.fail("random_orientation", "conflicts with a given orientation", "keep one of them");
    const Quat orientation = readOrientation(t);
    const long long seed = t.has("seed") ? t.integer("seed") : 1;
    readMotion(t, model);
    t.rejectUnknownKeys();

    scene.grains.reserve(static_cast<size_t>(before + wanted));
    std::mt19937_64 rng(static_cast<uint64_t>(seed));
    for (long long k = 0; k < count[2]; ++k)
        for (long long j = 0; j < count[1]; ++j)
            for (long long i = 0; i < count[0]; ++i) {
                GrainSpec g = model;
                if (!prefix.empty())
                    g.name = prefix + "_" + std::to_string(i) + "_" + std::to_string(j) + "_" +
                             std::to_string(k);
                g.pose.position = origin + Vec3(double(i) * spacing.x(), double(j) * spacing.y(),
                                                double(k) * spacing.z());
                if (jitter > 0.0)
                    for (int d = 0; d < 3; ++d)
                        g.pose.position[d] += jitter * (2.0 * uniform01(rng) - 1.0);
                g.pose.orientation = randomOrientation ? randomRotation([&] { return uniform01(rng); })
                                                       : orientation;
                scene.grains.push_back(g);
            }
}

} // namespace lsdem::scenefile
