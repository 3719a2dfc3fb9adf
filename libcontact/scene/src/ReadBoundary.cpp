// [[boundaries]]: planes (fixed, moving, or keeping a stress), spheres, level-set obstacles and
// cylinders (containers), orifice plates (a silo's floor).
#include "SceneSections.h"

#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/ServoKeys.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace lsdem::scenefile {

namespace {

/// A boundary's name becomes part of a file name (boundary_<name>.csv).
bool isFileNameSafe(const std::string& s)
{
    if (s.empty()) return false;
    for (char ch : s)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
}

/// A plane's stress servo: its keys read in their types, then the servo's rules
/// (ServoKeys.h). Nothing unless stress is given.
void readServo(TableReader& t, BoundarySpec& b)
{
    ServoKeys keys;
    const auto number = [&t](const char* key) {
        return t.has(key) ? std::optional<double>(t.number(key)) : std::nullopt;
    };
    keys.stress = number("stress");
    keys.area = number("area");
    keys.maxSpeed = number("max_speed");
    keys.gain = number("servo_gain");
    keys.velocityGiven = t.has("velocity");
    if (t.has("area_walls")) {
        const toml::array* a = t.node("area_walls").as_array();
        if (!a || !std::all_of(a->begin(), a->end(), [](const toml::node& e) { return e.is_string(); }))
            t.fail("area_walls", "expected the names of four walls (two opposite pairs)",
                   "write e.g. area_walls = [\"left\", \"right\", \"front\", \"back\"]");
        keys.areaWalls.emplace();
        for (const toml::node& e : *a) keys.areaWalls->push_back(e.as_string()->get());
    }
    if (std::optional<ServoProblem> p = applyServoKeys(keys, b)) t.fail(p->key, p->problem, p->fix);
}

} // namespace

BoundarySpec readBoundary(TableReader& t, const Scene& scene)
{
    BoundarySpec b;
    b.where = t.where();
    b.name = t.string("name");
    if (!isFileNameSafe(b.name))
        t.fail("name", "'" + b.name + "' cannot name a file (boundary_<name>.csv)",
               "use letters, digits, '_' and '-' only");
    const std::string type =
        t.choice("type", {"plane", "sphere", "level-set", "cylinder", "orifice"}, "");
    if (type.empty())
        t.fail("", "missing key 'type'",
               "add type = \"plane\" | \"sphere\" | \"level-set\" | \"cylinder\" | "
               "\"orifice\"");
    b.material = lookUpMaterial(t, scene);
    b.velocity = t.vec3("velocity", Vec3::Zero());
    if (type != "plane")
        for (const char* key : {"stress", "area", "area_walls", "max_speed", "servo_gain"})
            if (t.has(key))
                t.fail(key, "only a plane can keep a stress",
                       "use type = \"plane\" or remove " + std::string(key));
    if (type == "plane") {
        b.shape = BoundaryShape::Plane;
        b.point = t.vec3("point");
        b.normal = t.unitVec3("normal");
        if (t.has("extent")) {
            const std::vector<double> e = t.numbers("extent", 2);
            if (!(e[0] > 0.0 && e[1] > 0.0))
                t.fail("extent", "both widths must be > 0", "omit extent for an unbounded plane");
            b.extentU = e[0];
            b.extentV = e[1];
            b.axisU = t.has("axis_u") ? t.unitVec3("axis_u") : b.normal.unitOrthogonal();
            // Keep only the in-plane part, so a slightly off axis still defines the patch.
            const Vec3 inPlane = b.axisU - b.axisU.dot(b.normal) * b.normal;
            if (inPlane.norm() < 1e-6)
                t.fail("axis_u", "is parallel to the normal", "give a direction within the plane");
            b.axisU = inPlane.normalized();
        } else if (t.has("axis_u")) {
            t.fail("axis_u", "only makes sense with extent", "add extent = [wu, wv] or remove it");
        }
        b.thickness = t.has("thickness") ? t.positive("thickness") : 0.0;
        readServo(t, b);
    } else if (type == "sphere") {
        b.shape = BoundaryShape::Sphere;
        b.center = t.vec3("center");
        b.radius = t.positive("radius");
    } else if (type == "cylinder") {
        b.shape = BoundaryShape::Cylinder;
        b.center = t.vec3("center");
        b.axis = t.has("axis") ? t.unitVec3("axis") : Vec3::UnitZ();
        b.radius = t.positive("radius");
    } else if (type == "orifice") {
        b.shape = BoundaryShape::Orifice;
        b.center = t.vec3("center");
        b.axis = t.has("axis") ? t.unitVec3("axis") : Vec3::UnitZ();
        b.radius = t.positive("radius");
        b.thickness = t.positive("thickness");
    } else {
        b.shape = BoundaryShape::LevelSet;
        b.asset = lookUpAsset(t, scene);
        b.pose.position = t.vec3("position");
        b.pose.orientation = readOrientation(t);
    }
    t.rejectUnknownKeys();
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
