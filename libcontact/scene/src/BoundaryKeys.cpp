#include "lsdem/scene/BoundaryKeys.h"

#include "lsdem/scene/EntryRules.h"

#include "lsdem/core/NumberRange.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace lsdem {

namespace {

const std::vector<std::string> kServoKeyNames = {"stress", "area", "area_walls", "max_speed",
                                                 "servo_gain"};

/// A boundary's name becomes part of a file name (boundary_<name>.csv).
bool isFileNameSafe(const std::string& s)
{
    if (s.empty()) return false;
    for (char ch : s)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
}

/// The keys of @a k that are given, besides the common ones, by their names in a file.
std::vector<std::string> givenKeys(const BoundaryKeys& k)
{
    std::vector<std::string> given;
    const auto note = [&given](const char* key, bool present) {
        if (present) given.emplace_back(key);
    };
    note("point", k.point.has_value());
    note("normal", k.normal.has_value());
    note("extent", k.extent.has_value());
    note("axis_u", k.axisU.has_value());
    note("thickness", k.thickness.has_value());
    note("center", k.center.has_value());
    note("radius", k.radius.has_value());
    note("axis", k.axis.has_value());
    note("asset", k.asset.has_value());
    note("position", k.position.has_value());
    note("orientation", k.orientation.has_value());
    note("stress", k.servo.stress.has_value());
    note("area", k.servo.area.has_value());
    note("area_walls", k.servo.areaWalls.has_value());
    note("max_speed", k.servo.maxSpeed.has_value());
    note("servo_gain", k.servo.gain.has_value());
    return given;
}

bool contains(const std::vector<std::string>& list, const std::string& word)
{
    return std::find(list.begin(), list.end(), word) != list.end();
}

std::string listed(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
    return s;
}

/// The keys @a k gives that its type does not take, then those it needs and lacks.
std::optional<KeyProblem> keysProblem(const BoundaryKeys& k, const BoundaryType& type)
{
    const std::vector<std::string> given = givenKeys(k);
    for (const std::string& key : given) {
        if (contains(type.required, key) || contains(type.optional, key)) continue;
        if (contains(kServoKeyNames, key))
            return KeyProblem{key, "only a plane can keep a stress",
                                   "use type = \"plane\" or remove " + key};
        std::vector<std::string> keys = type.required;
        keys.insert(keys.end(), type.optional.begin(), type.optional.end());
        return KeyProblem{key, "a " + type.name + " boundary takes no '" + key + "'",
                               "remove it; a " + type.name + " takes " + listed(keys) +
                                   " (and name, type, material, velocity)"};
    }
    for (const std::string& key : type.required)
        if (!contains(given, key))
            return KeyProblem{"", "missing key '" + key + "'", "add " + key + " = ..."};
    return std::nullopt;
}

std::optional<KeyProblem> sizeProblem(const char* key, const std::optional<double>& size)
{
    if (!size) return std::nullopt;
    if (std::optional<std::string> p = outOfRange(NumberRange::Positive, *size))
        return KeyProblem{key, *p, "give a positive length"};
    return std::nullopt;
}

std::optional<KeyProblem> directionProblem(const char* key, const std::optional<Vec3>& v)
{
    if (v && !(v->norm() > 0.0))
        return KeyProblem{key, "must not be the zero vector", "give a direction"};
    return std::nullopt;
}

/// The values' rules: finite vectors, non-zero directions, a patch's widths and axis, sizes.
std::optional<KeyProblem> valuesProblem(const BoundaryKeys& k)
{
    for (const auto& [key, v] : {std::pair<const char*, const std::optional<Vec3>*>{"velocity", &k.velocity},
                                 {"point", &k.point}, {"normal", &k.normal}, {"axis_u", &k.axisU},
                                 {"center", &k.center}, {"axis", &k.axis},
                                 {"position", &k.position}})
        if (auto p = nonFiniteProblem(key, *v)) return p;
    for (const auto& [key, v] : {std::pair<const char*, const std::optional<Vec3>*>{"normal", &k.normal},
                                 {"axis", &k.axis}, {"axis_u", &k.axisU}})
        if (auto p = directionProblem(key, *v)) return p;
    if (k.extent && !((*k.extent)[0] > 0.0 && (*k.extent)[1] > 0.0 &&
                      std::isfinite((*k.extent)[0]) && std::isfinite((*k.extent)[1])))
        return KeyProblem{"extent", "both widths must be > 0",
                               "omit extent for an unbounded plane"};
    if (k.axisU && !k.extent)
        return KeyProblem{"axis_u", "only makes sense with extent",
                               "add extent = [wu, wv] or remove it"};
    if (auto p = sizeProblem("radius", k.radius)) return p;
    if (auto p = sizeProblem("thickness", k.thickness)) return p;
    if (k.orientation)
        if (std::optional<std::string> p = orientationProblem(*k.orientation))
            return KeyProblem{"orientation", *p, kOrientationFix};
    return std::nullopt;
}

/// A patch's first axis: the in-plane part of what was given, so a slightly tilted axis still
/// defines the patch; none if it is along the normal.
std::optional<Vec3> inPlaneAxis(const Vec3& axisU, const Vec3& normal)
{
    const Vec3 inPlane = axisU - axisU.dot(normal) * normal;
    if (!(inPlane.norm() >= 1e-6)) return std::nullopt;
    return unitVector(inPlane);
}

} // namespace

const std::vector<BoundaryType>& boundaryTypes()
{
    static const std::vector<BoundaryType> types = {
        {"plane", BoundaryShape::Plane, {"point", "normal"},
         {"extent", "axis_u", "thickness", "stress", "area", "area_walls", "max_speed",
          "servo_gain"},
         "on the side the normal points to"},
        {"sphere", BoundaryShape::Sphere, {"center", "radius"}, {}, "outside it"},
        {"level-set", BoundaryShape::LevelSet, {"asset", "position"}, {"orientation"},
         "outside it"},
        {"cylinder", BoundaryShape::Cylinder, {"center", "radius"}, {"axis"}, "inside it"},
        {"orifice", BoundaryShape::Orifice, {"center", "radius", "thickness"}, {"axis"},
         "outside the plate, on either side"},
    };
    return types;
}

const BoundaryType* boundaryType(const std::string& name)
{
    for (const BoundaryType& t : boundaryTypes())
        if (t.name == name) return &t;
    return nullptr;
}

const BoundaryType& boundaryTypeOf(BoundaryShape shape)
{
    for (const BoundaryType& t : boundaryTypes())
        if (t.shape == shape) return t;
    return boundaryTypes().front();  // unreachable: every shape has a type
}

std::optional<KeyProblem> applyBoundaryKeys(const BoundaryKeys& k, BoundarySpec& out)
{
    if (!isFileNameSafe(k.name))
        return KeyProblem{"name", "'" + k.name + "' cannot name a file (boundary_<name>.csv)",
                               "use letters, digits, '_' and '-' only"};
    std::vector<std::string> typeNames;
    for (const BoundaryType& t : boundaryTypes()) typeNames.push_back("\"" + t.name + "\"");
    if (k.type.empty())
        return KeyProblem{"", "missing key 'type'", "add type = " + listed(typeNames)};
    const BoundaryType* type = boundaryType(k.type);
    if (!type)
        return KeyProblem{"type", "unknown value '" + k.type + "'",
                               "use one of: " + listed(typeNames)};
    if (auto p = keysProblem(k, *type)) return p;
    if (auto p = valuesProblem(k)) return p;

    BoundarySpec b;
    b.name = k.name;
    b.shape = type->shape;
    b.material = k.material;
    b.velocity = k.velocity.value_or(Vec3::Zero());
    b.point = k.point.value_or(b.point);
    if (k.normal) b.normal = unitVector(*k.normal);
    if (k.extent) {
        b.extentU = (*k.extent)[0];
        b.extentV = (*k.extent)[1];
        const std::optional<Vec3> u =
            inPlaneAxis(k.axisU ? unitVector(*k.axisU) : b.normal.unitOrthogonal(), b.normal);
        if (!u)
            return KeyProblem{"axis_u", "is parallel to the normal",
                                   "give a direction within the plane"};
        b.axisU = *u;
    }
    b.thickness = k.thickness.value_or(0.0);
    b.center = k.center.value_or(b.center);
    b.radius = k.radius.value_or(0.0);
    if (k.axis) b.axis = unitVector(*k.axis);
    b.asset = k.asset.value_or(-1);
    b.pose.position = k.position.value_or(Vec3::Zero());
    b.pose.orientation = k.orientation.value_or(Quat::Identity());

    ServoKeys servo = k.servo;
    servo.velocityGiven = k.velocity.has_value() && !k.velocity->isZero(0.0);
    if (std::optional<KeyProblem> p = applyServoKeys(servo, b)) return p;
    b.where = out.where;
    out = std::move(b);
    return std::nullopt;
}

BoundaryKeys boundaryKeysOf(const BoundarySpec& b, const Scene& scene)
{
    BoundaryKeys k;
    k.name = b.name;
    k.type = boundaryTypeOf(b.shape).name;
    k.material = b.material;
    if (!b.velocity.isZero(0.0)) k.velocity = b.velocity;
    switch (b.shape) {
    case BoundaryShape::Plane:
        k.point = b.point;
        k.normal = b.normal;
        if (b.extentU != 0.0 || b.extentV != 0.0) {
            k.extent = std::array<double, 2>{b.extentU, b.extentV};
            k.axisU = b.axisU;
        }
        if (b.thickness != 0.0) k.thickness = b.thickness;
        break;
    case BoundaryShape::Sphere:
        k.center = b.center;
        k.radius = b.radius;
        break;
    case BoundaryShape::Cylinder:
    case BoundaryShape::Orifice:
        k.center = b.center;
        k.axis = b.axis;
        k.radius = b.radius;
        if (b.shape == BoundaryShape::Orifice) k.thickness = b.thickness;
        break;
    case BoundaryShape::LevelSet:
        k.asset = b.asset;
        k.position = b.pose.position;
        k.orientation = b.pose.orientation;
        break;
    }
    const StressServo& s = b.servo;
    if (s.targetStress != 0.0) {  // not active() alone: a negative stress must be refused
        k.servo.stress = s.targetStress;
        if (s.areaFromWalls()) {
            std::vector<std::string> names;
            for (int w : s.areaWalls)
                names.push_back(w >= 0 && size_t(w) < scene.boundaries.size()
                                    ? scene.boundaries[size_t(w)].name
                                    : std::string());
            k.servo.areaWalls = names;
        } else {
            k.servo.area = s.area;
        }
        k.servo.maxSpeed = s.maxSpeed;
        k.servo.gain = s.gain;
    }
    return k;
}

} // namespace lsdem
