// [[boundaries]]: planes (fixed, moving, or keeping a stress), spheres, level-set obstacles and
// cylinders (containers), orifice plates (a silo's floor).
#include "SceneSections.h"

#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/BoundaryKeys.h"

#include <algorithm>
#include <cmath>

namespace lsdem::scenefile {

namespace {

/// area_walls = ["left", "right", "front", "back"]: the names as given (their rules are the
/// servo's, ServoKeys.h).
std::vector<std::string> readAreaWalls(TableReader& t)
{
    const toml::array* a = t.node("area_walls").as_array();
    if (!a || !std::all_of(a->begin(), a->end(), [](const toml::node& e) { return e.is_string(); }))
        t.fail("area_walls", "expected the names of four walls (two opposite pairs)",
               "write e.g. area_walls = [\"left\", \"right\", \"front\", \"back\"]");
    std::vector<std::string> names;
    for (const toml::node& e : *a) names.push_back(e.as_string()->get());
    return names;
}

} // namespace

// Every key the schema knows is gathered in its type, whatever the entry's type; the schema
// (BoundaryKeys.h) then says which of them this type takes, needs, and in what range.
BoundarySpec readBoundary(TableReader& t, const Scene& scene)
{
    BoundaryKeys k;
    k.name = t.string("name");
    k.type = t.string("type", "");
    k.material = lookUpMaterial(t, scene);
    const auto vector = [&t](const char* key) {
        return t.has(key) ? std::optional<Vec3>(t.vec3(key)) : std::nullopt;
    };
    const auto number = [&t](const char* key) {
        return t.has(key) ? std::optional<double>(t.number(key)) : std::nullopt;
    };
    k.velocity = vector("velocity");
    k.point = vector("point");
    k.normal = vector("normal");
    if (t.has("extent")) {
        const std::vector<double> e = t.numbers("extent", 2);
        k.extent = std::array<double, 2>{e[0], e[1]};
    }
    k.axisU = vector("axis_u");
    k.thickness = number("thickness");
    k.center = vector("center");
    k.radius = number("radius");
    k.axis = vector("axis");
    if (t.has("asset")) k.asset = lookUpAsset(t, scene);
    k.position = vector("position");
    if (t.has("orientation") || t.has("axis_angle")) k.orientation = readOrientation(t);
    k.servo.stress = number("stress");
    k.servo.area = number("area");
    if (t.has("area_walls")) k.servo.areaWalls = readAreaWalls(t);
    k.servo.maxSpeed = number("max_speed");
    k.servo.gain = number("servo_gain");
    t.rejectUnknownKeys();

    BoundarySpec b;
    b.where = t.where();
    if (std::optional<KeyProblem> p = applyBoundaryKeys(k, b)) t.fail(p->key, p->problem, p->fix);
    return b;
}

} // namespace lsdem::scenefile

namespace lsdem {

void resolveServoAreaWalls(Scene& scene)
{
    const double parallel = 1e-6;  // |cos| tolerance: the walls of a cuboid cell are exact
    for (BoundarySpec& b : scene.boundaries) {
        if (b.areaWallNames.empty()) continue;
        const std::string label = "[[boundaries]] '" + b.name + "' area_walls: ";
        for (size_t k = 0; k < 4; ++k) {
            const std::string& name = b.areaWallNames[k];
            const int i = scenefile::indexByName(scene.boundaries, name);
            if (i < 0)
                throw Error(b.where, label + "no boundary named '" + name + "'",
                            "name four plane walls of the scene");
            const BoundarySpec& w = scene.boundaries[static_cast<size_t>(i)];
            if (&w == &b || w.shape != BoundaryShape::Plane)
                throw Error(b.where, label + "'" + name + "' " +
                                         (&w == &b ? "is the wall itself" : "is not a plane"),
                            "name the plane walls around it, two opposite pairs");
            if (std::abs(w.normal.dot(b.normal)) > parallel)
                throw Error(b.where, label + "'" + name + "' is not perpendicular to the wall",
                            "name the walls that bound it sideways");
            b.servo.areaWalls[k] = i;
        }
        for (size_t pair = 0; pair < 2; ++pair) {
            const BoundarySpec& w0 = scene.boundaries[size_t(b.servo.areaWalls[2 * pair])];
            const BoundarySpec& w1 = scene.boundaries[size_t(b.servo.areaWalls[2 * pair + 1])];
            if (w0.normal.dot(w1.normal) > -1.0 + parallel)
                throw Error(b.where,
                            label + "'" + w0.name + "' and '" + w1.name + "' are not opposite walls",
                            "list two pairs of walls whose normals point at each other");
            if (!((w1.point - w0.point).dot(w0.normal) > 0.0))
                throw Error(b.where,
                            label + "'" + w0.name + "' and '" + w1.name + "' enclose no space",
                            "each wall's normal points towards the grains, so towards the other");
        }
        const BoundarySpec& u = scene.boundaries[size_t(b.servo.areaWalls[0])];
        const BoundarySpec& v = scene.boundaries[size_t(b.servo.areaWalls[2])];
        if (std::abs(u.normal.dot(v.normal)) > parallel)
            throw Error(b.where, label + "the pairs '" + u.name + "' and '" + v.name +
                                     "' are not perpendicular",
                        "list the x pair and then the y pair (or any two perpendicular pairs)");
    }
}

} // namespace lsdem
