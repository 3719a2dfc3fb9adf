// [[boundaries]]: planes, spheres and level-set obstacles.
#include "SceneSections.h"

#include <cctype>

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

} // namespace

BoundarySpec readBoundary(TableReader& t, const Scene& scene)
{
    BoundarySpec b;
    b.where = t.where();
    b.name = t.string("name");
    if (!isFileNameSafe(b.name))
        t.fail("name", "'" + b.name + "' cannot name a file (boundary_<name>.csv)",
               "use letters, digits, '_' and '-' only");
    const std::string type = t.choice("type", {"plane", "sphere", "level-set"}, "");
    if (type.empty()) t.fail("", "missing key 'type'", "add type = \"plane\" | \"sphere\" | \"level-set\"");
    b.material = lookUpMaterial(t, scene);
    b.velocity = t.vec3("velocity", Vec3::Zero());
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
    } else if (type == "sphere") {
        b.shape = BoundaryShape::Sphere;
        b.center = t.vec3("center");
        b.radius = t.positive("radius");
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
