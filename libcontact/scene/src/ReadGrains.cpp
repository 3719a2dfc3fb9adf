// [[grains]] and [[lattices]]: grains one by one or in blocks, with their orientation and
// motion.
#include "SceneSections.h"

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/GrainKeys.h"

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

namespace {

/// The keys a grain and a lattice's grains share (GrainKeys.h): asset, material, motion,
/// velocities and mass. The position and orientation are each caller's own.
GrainKeys readSharedGrainKeys(TableReader& t, const Scene& scene)
{
    GrainKeys k;
    k.asset = lookUpAsset(t, scene);
    k.material = lookUpMaterial(t, scene);
    if (t.has("motion")) k.motion = t.string("motion");
    if (t.has("velocity")) k.velocity = t.vec3("velocity");
    if (t.has("angular_velocity")) k.angularVelocity = t.vec3("angular_velocity");
    if (t.has("mass")) k.mass = t.number("mass");
    return k;
}

/// The grain @a k gives, by the schema's rules, or the file's error at the key at fault.
GrainSpec grainOf(TableReader& t, const GrainKeys& k)
{
    GrainSpec g;
    g.where = t.where();
    if (std::optional<KeyProblem> p = applyGrainKeys(k, g)) t.fail(p->key, p->problem, p->fix);
    return g;
}

} // namespace

GrainSpec readGrain(TableReader& t, const Scene& scene)
{
    const std::string name = t.string("name", "");
    GrainKeys k = readSharedGrainKeys(t, scene);
    k.name = name;
    if (t.has("position")) k.position = t.vec3("position");
    k.orientation = readOrientation(t);
    t.rejectUnknownKeys();
    return grainOf(t, k);
}

/// A block of count[0]×count[1]×count[2] grains at origin + (i, j, k)·spacing, optionally
/// jittered and randomly turned (seeded, reproducible everywhere).
void readLattice(TableReader& t, Scene& scene)
{
    const std::string prefix = t.string("name", "");
    GrainKeys keys = readSharedGrainKeys(t, scene);
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
    t.rejectUnknownKeys();
    keys.position = origin;
    keys.orientation = orientation;
    const GrainSpec model = grainOf(t, keys);

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
