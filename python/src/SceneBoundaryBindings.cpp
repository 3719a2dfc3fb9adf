// Scene builder methods in Python: walls (with an optional stress servo), containers, an
// orifice plate and an indenter, checked as the scene reader checks [[boundaries]].
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/ServoKeys.h"

#include <pybind11/stl.h>

#include <cmath>
#include <optional>

namespace lsdem::python {

namespace {

/// A plane's stress servo from the keyword arguments of add_plane, by the rules a file's
/// [[boundaries]] servo keys obey (ServoKeys.h). Nothing unless @a stress is given.
void setServo(BoundarySpec& b, const std::optional<double>& stress,
              const std::optional<double>& area,
              const std::optional<std::vector<std::string>>& areaWalls,
              const std::optional<double>& maxSpeed, const std::optional<double>& gain)
{
    const ServoKeys keys{stress, area, areaWalls, maxSpeed, gain, !b.velocity.isZero(0.0)};
    if (std::optional<ServoProblem> p = applyServoKeys(keys, b))
        throw Error("", "boundary '" + b.name + "': " + p->key + " " + p->problem, p->fix);
}

/// A boundary about an axis (a cylinder's side wall, an orifice plate), checked as the scene
/// reader checks it: a new name, a positive radius, a non-zero axis (made unit).
BoundarySpec axialBoundary(const Scene& s, const std::string& name, const std::string& material,
                           BoundaryShape shape, const py::object& center, double radius,
                           const py::object& axis, const py::object& velocity)
{
    checkNewName(s.boundaries, name, "boundary");
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw Error("", "boundary '" + name + "': radius must be > 0");
    BoundarySpec b;
    b.name = name;
    b.shape = shape;
    b.material = indexOf(s.materials, material, "material");
    b.center = toVec3(center, "center");
    b.axis = toVec3(axis, "axis");
    if (!(b.axis.norm() > 0.0))
        throw Error("", "boundary '" + name + "': the axis must not be zero");
    b.axis.normalize();
    b.radius = radius;
    b.velocity = toVec3(velocity, "velocity");
    b.where = "boundary '" + name + "'";
    return b;
}

} // namespace

// Long by nature: one .def per builder method, each with its keyword arguments and docstring.
void bindSceneBoundaries(py::class_<Scene>& scene)
{
    scene
        .def("add_plane",
             [](Scene& s, const std::string& name, const std::string& material,
                const py::object& point, const py::object& normal, const py::object& velocity,
                std::optional<double> stress, std::optional<double> area,
                std::optional<std::vector<std::string>> areaWalls,
                std::optional<double> maxSpeed, std::optional<double> servoGain) {
                 checkNewName(s.boundaries, name, "boundary");
                 BoundarySpec b;
                 b.name = name;
                 b.shape = BoundaryShape::Plane;
                 b.material = indexOf(s.materials, material, "material");
                 b.point = toVec3(point, "point");
                 b.normal = toVec3(normal, "normal");
                 if (!(b.normal.norm() > 0.0)) throw Error("", "the normal must not be zero");
                 b.normal.normalize();
                 b.velocity = toVec3(velocity, "velocity");
                 b.where = "boundary '" + name + "'";
                 setServo(b, stress, area, areaWalls, maxSpeed, servoGain);
                 s.boundaries.push_back(b);
                 if (!b.areaWallNames.empty()) {
                     try {  // the walls it names must be in the scene already
                         resolveServoAreaWalls(s);
                     } catch (const Error&) {
                         s.boundaries.pop_back();
                         throw;
                     }
                 }
                 markChanged(s);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("point"),
             py::arg("normal"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("stress") = py::none(), py::arg("area") = py::none(),
             py::arg("area_walls") = py::none(), py::arg("max_speed") = py::none(),
             py::arg("servo_gain") = py::none(),
             "An unbounded wall through `point`; grains live on the side `normal` points to. "
             "It moves at `velocity` whatever the forces (zero: fixed).\n\n"
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
                 BoundarySpec b = axialBoundary(s, name, material, BoundaryShape::Cylinder,
                                                center, radius, axis, velocity);
                 markChanged(s);
                 s.boundaries.push_back(b);
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
                 BoundarySpec b = axialBoundary(s, name, material, BoundaryShape::Orifice,
                                                center, radius, axis, velocity);
                 if (!(thickness > 0.0) || !std::isfinite(thickness))
                     throw Error("", "boundary '" + name + "': thickness must be > 0");
                 b.thickness = thickness;
                 markChanged(s);
                 s.boundaries.push_back(b);
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
                 checkNewName(s.boundaries, name, "boundary");
                 if (!(radius > 0.0) || !std::isfinite(radius))
                     throw Error("", "boundary '" + name + "': radius must be > 0");
                 BoundarySpec b;
                 b.name = name;
                 b.shape = BoundaryShape::Sphere;
                 b.material = indexOf(s.materials, material, "material");
                 b.center = toVec3(center, "center");
                 b.radius = radius;
                 b.velocity = toVec3(velocity, "velocity");
                 b.where = "boundary '" + name + "'";
                 markChanged(s);
                 s.boundaries.push_back(b);
             },
             py::arg("name"), py::arg("material"), py::kw_only(), py::arg("center"),
             py::arg("radius"), py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             "A rigid sphere (an indenter); grains live outside it.");
}

} // namespace lsdem::python
