#include "lsdem/scene/GrainKeys.h"

#include "lsdem/core/NumberRange.h"

namespace lsdem {

namespace {

std::string motionChoices()
{
    std::string s;
    for (const std::string& m : grainMotionNames()) s += (s.empty() ? "" : ", ") + m;
    return s;
}

} // namespace

std::optional<KeyProblem> applyGrainKeys(const GrainKeys& k, GrainSpec& out)
{
    if (!k.position) return KeyProblem{"", "missing key 'position'", "add position = [x, y, z]"};
    for (const auto& [key, v] : {std::pair{"position", &k.position}, {"velocity", &k.velocity},
                                 {"angular_velocity", &k.angularVelocity}})
        if (auto p = nonFiniteProblem(key, *v)) return p;
    if (k.orientation)
        if (std::optional<std::string> p = orientationProblem(*k.orientation))
            return KeyProblem{"orientation", *p, kOrientationFix};
    const std::optional<GrainMotion> motion =
        k.motion ? parseGrainMotion(*k.motion) : std::optional<GrainMotion>(GrainMotion::Free);
    if (!motion)
        return KeyProblem{"motion", "unknown value '" + *k.motion + "'",
                          "use one of: " + motionChoices()};
    if (*motion == GrainMotion::Fixed)
        for (const auto& [key, v] : {std::pair{"velocity", &k.velocity},
                                     {"angular_velocity", &k.angularVelocity}})
            if (*v && !(*v)->isZero(0.0))
                return KeyProblem{key, "must be zero, as a fixed grain cannot move",
                                  "remove the velocity, or make its motion \"prescribed\" to move "
                                  "it at that velocity"};
    if (k.mass)
        if (std::optional<std::string> p = outOfRange(NumberRange::NonNegative, *k.mass))
            return KeyProblem{"mass", *p, "give the grain's mass, or 0 for density × volume"};

    GrainSpec g;
    g.name = k.name;
    g.asset = k.asset;
    g.material = k.material;
    g.pose.position = *k.position;
    g.pose.orientation = k.orientation ? unitQuaternion(*k.orientation) : Quat::Identity();
    g.motion = *motion;
    g.velocity = k.velocity.value_or(Vec3::Zero());
    g.angularVelocity = k.angularVelocity.value_or(Vec3::Zero());
    g.mass = k.mass.value_or(0.0);
    g.where = out.where;
    out = std::move(g);
    return std::nullopt;
}

GrainKeys grainKeysOf(const GrainSpec& g)
{
    GrainKeys k;
    k.name = g.name;
    k.asset = g.asset;
    k.material = g.material;
    k.position = g.pose.position;
    k.orientation = g.pose.orientation;
    if (g.motion != GrainMotion::Free) k.motion = grainMotionName(g.motion);
    if (!g.velocity.isZero(0.0)) k.velocity = g.velocity;
    if (!g.angularVelocity.isZero(0.0)) k.angularVelocity = g.angularVelocity;
    if (g.mass != 0.0) k.mass = g.mass;
    return k;
}

} // namespace lsdem
