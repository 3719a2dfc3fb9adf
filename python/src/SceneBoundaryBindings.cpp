// Scene builder methods in Python: walls (with an optional stress servo), containers, an
// orifice plate, an indenter and level-set obstacles, checked by the rules the scene reader
// applies to [[boundaries]] (BoundaryKeys.h).
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/BoundaryKeys.h"

#include <pybind11/stl.h>

#include <array>
#include <optional>

namespace lsdem::python {

namespace {

/// Optional arguments as the schema's optional keys (None: not given).
std::optional<Vec3> optionalVec3(const py::object& value, const std::string& what)
{
    return value.is_none() ? std::nullopt : std::optional<Vec3>(toVec3(value, what));
}

/// Adds the boundary @a keys give to @a s by the rules a file's [[boundaries]] entry obeys
/// (BoundaryKeys.h), in the same words; a servo's area walls must be in the scene already.
void addBoundary(Scene& s, const BoundaryKeys& keys)
{
    checkNewName(s.boundaries, keys.name, "boundary");
    BoundarySpec b;
    b.where = "boundary '" + keys.name + "'";
    if (std::optional<KeyProblem> p = applyBoundaryKeys(keys, b))
        throw Error("", "boundary '" + keys.name + "': " + keyProblemText(*p),
                    p->fix);
    s.boundaries.push_back(b);
    if (!b.areaWallNames.empty()) {
        try {
            resolveServoAreaWalls(s);
        } catch (const Error&) {
            s.boundaries.pop_back();
            throw;
        }
    }
    markChanged(s);
}

/// The keys every boundary has: its name, type, material and velocity.
BoundaryKeys commonKeys(const Scene& s, const std::string& name, const std::string& type,
                        const std::string& material, const py::object& velocity)
{
    BoundaryKeys k;
    k.name = name;
    k.type = type;
    k.material = indexOf(s.materials, material, "material");
    k.velocity = toVec3(velocity, "velocity");
    return k;
}

} // namespace

// Long by nature: one .def per builder method, each with its keyword arguments and docstring.
void bindSceneBoundaries(py::class_<Scene>& scene)
{
    scene
        .def("add_plane",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& point, const py::object& normal, const py::object& velocity,
                std::optional<std::array<double, 2>> extent, const py::object& axisU,
                std::optional<double> thickness, std::optional<double> stress,
                std::optional<double> area, std::optional<std::vector<std::string>> areaWalls,
                std::optional<double> maxSpeed, std::optional<double> servoGain) {
                 BoundaryKeys k = commonKeys(s, name, "plane", material, velocity);
                 k.point = toVec3(point, "point");
                 k.normal = toVec3(normal, "normal");
                 k.extent = extent;
                 k.axisU = optionalVec3(axisU, "axis_u");
                 k.thickness = thickness;
                 k.servo = ServoKeys{stress, area, areaWalls, maxSpeed, servoGain, false};
                 addBoundary(s, k);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("point"),
             py::arg("normal"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("extent") = py::none(), py::arg("axis_u") = py::none(),
             py::arg("thickness") = py::none(), py::arg("stress") = py::none(),
             py::arg("area") = py::none(), py::arg("area_walls") = py::none(),
             py::arg("max_speed") = py::none(), py::arg("servo_gain") = py::none(),
             "A wall through `point`; grains live on the side `normal` points to. It moves at "
             "`velocity` whatever the forces (zero: fixed).\n\n"
             "Unbounded, or a rectangular patch `extent` = (wu, wv) wide along `axis_u` (default: "
             "any direction within the plane) and normal × `axis_u`; nodes more than `thickness` "
             "behind it are ignored (default: none are).\n\n"
             "With `stress` (> 0, force/length²) it is a servo wall instead (docs/packing.md): "
             "it moves along its normal to keep the grains' normal stress on it, over `area` "
             "(length²) or over the rectangle between `area_walls` (the names of two pairs of "
             "opposite plane walls perpendicular to it, added before it), at most at "
             "`max_speed` (required), closing the share `servo_gain` in (0, 1] (default 0.5) "
             "of the error per step.")
        .def("add_cylinder_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, const py::object& axis,
                const py::object& velocity) {
                 BoundaryKeys k = commonKeys(s, name, "cylinder", material, velocity);
                 k.center = toVec3(center, "center");
                 k.radius = radius;
                 k.axis = toVec3(axis, "axis");
                 addBoundary(s, k);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "The side wall of an infinitely long cylinder through `center` along `axis`; "
             "grains live inside it (a container: add planes for its floor and lid).")
        .def("add_orifice_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, double thickness,
                const py::object& axis, const py::object& velocity) {
                 BoundaryKeys k = commonKeys(s, name, "orifice", material, velocity);
                 k.center = toVec3(center, "center");
                 k.radius = radius;
                 k.thickness = thickness;
                 k.axis = toVec3(axis, "axis");
                 addBoundary(s, k);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("thickness"),
             py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "A flat plate of `thickness` with a circular hole of `radius` (a silo's floor "
             "and its orifice): `center` is the hole's centre in the plate's mid-plane, `axis` "
             "the plate's normal; grains live outside the plate, on either side.");
    scene
        .def("add_sphere_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& center, double radius, const py::object& velocity) {
                 BoundaryKeys k = commonKeys(s, name, "sphere", material, velocity);
                 k.center = toVec3(center, "center");
                 k.radius = radius;
                 addBoundary(s, k);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "A rigid sphere (an indenter); grains live outside it.")
        .def("add_level_set_boundary",
             [](Scene& s, const std::string& name, const std::string& material,
                const std::string& asset, const py::object& position,
                const py::object& orientation, const py::object& velocity) {
                 BoundaryKeys k = commonKeys(s, name, "level-set", material, velocity);
                 k.asset = indexOf(s.assets, asset, "asset");
                 k.position = toVec3(position, "position");
                 k.orientation = toQuat(orientation);
                 addBoundary(s, k);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("asset"),
             py::arg("position"), py::arg("orientation") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "An asset of the scene as a rigid obstacle (an indenter of any shape, a rough "
             "floor): its centroid at `position`, turned by the unit quaternion `orientation` "
             "[w, x, y, z] (asset frame to world); grains live outside it.");
}

} // namespace lsdem::python
