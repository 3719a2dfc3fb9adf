// sim.grains and sim.boundaries in Python: numpy views into the running world where the data
// is stored as such, copies where it is computed.
#include "PySimulation.h"

namespace lsdem::python {

namespace {

const char* shapeName(BoundaryShape s)
{
    switch (s) {
    case BoundaryShape::Plane: return "plane";
    case BoundaryShape::Sphere: return "sphere";
    case BoundaryShape::LevelSet: return "level-set";
    case BoundaryShape::Cylinder: return "cylinder";
    case BoundaryShape::Orifice: return "orifice";
    }
    return "?";
}

} // namespace

// Long by nature: the three view classes' .defs, one per property, as help() lists them.
void bindSimulationViews(py::module_& m)
{
    py::class_<GrainsView>(
        m, "Grains",
        "The grains of a running simulation, in scene order. positions, velocities, forces "
        "and torques are read-only numpy views into the simulation (no copy; they follow it "
        "as it steps and keep it alive); the other arrays are fresh copies.")
        .def("__len__", [](const GrainsView& g) { return g.world().grains.size(); })
        .def_property_readonly("names",
                               [](const GrainsView& g) {
                                   std::vector<std::string> names;
                                   for (const Grain& grain : g.world().grains)
                                       names.push_back(grain.name);
                                   return names;
                               })
        .def_property_readonly(
            "positions",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.body.pose.position; });
            },
            "(N, 3) float64 view: centroid positions (length).")
        .def_property_readonly(
            "unwrapped_positions",
            [](const GrainsView& g) {
                const std::vector<Grain>& grains = g.world().grains;
                py::array_t<double> out({static_cast<py::ssize_t>(grains.size()), py::ssize_t{3}});
                auto o = out.mutable_unchecked<2>();
                for (size_t i = 0; i < grains.size(); ++i) {
                    const Vec3 x = grains[i].unwrappedPosition();
                    for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = x[k];
                }
                return out;
            },
            "(N, 3) float64 copy: in a periodic cell, where each grain's motion took it (its "
            "position less the periods it was brought back by, which the cell's deformation "
            "stretches); elsewhere the positions.")
        .def_property_readonly(
            "velocities",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.body.velocity; });
            },
            "(N, 3) float64 view: centroid velocities (length/time).")
        .def_property_readonly(
            "forces",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.force; });
            },
            "(N, 3) float64 view: total force on each grain at the last evaluation.")
        .def_property_readonly(
            "torques",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.torque; });
            },
            "(N, 3) float64 view: torque about each centroid at the last evaluation.")
        .def_property_readonly(
            "orientations",
            [](const GrainsView& g) {
                const std::vector<Grain>& grains = g.world().grains;
                py::array_t<double> out({static_cast<py::ssize_t>(grains.size()), py::ssize_t{4}});
                auto o = out.mutable_unchecked<2>();
                for (size_t i = 0; i < grains.size(); ++i) {
                    const Quat& q = grains[i].body.pose.orientation;
                    const auto r = static_cast<py::ssize_t>(i);
                    o(r, 0) = q.w(), o(r, 1) = q.x(), o(r, 2) = q.y(), o(r, 3) = q.z();
                }
                return out;
            },
            "(N, 4) float64 copy: unit quaternions [w, x, y, z], asset frame to world.")
        .def_property_readonly(
            "angular_velocities",
            [](const GrainsView& g) {
                std::vector<Vec3> omega;
                for (const Grain& grain : g.world().grains) omega.push_back(grain.angularVelocity());
                return vectorCopy(omega);
            },
            "(N, 3) float64 copy: world angular velocities (rad/time).")
        .def_property_readonly(
            "masses",
            [](const GrainsView& g) {
                const std::vector<Grain>& grains = g.world().grains;
                py::array_t<double> out(static_cast<py::ssize_t>(grains.size()));
                for (size_t i = 0; i < grains.size(); ++i)
                    out.mutable_at(static_cast<py::ssize_t>(i)) = grains[i].body.mass;
                return out;
            },
            "(N,) float64 copy: masses.");

    py::class_<BoundaryView>(m, "Boundary",
                             "One boundary of a running simulation (a wall, an indenter or a "
                             "level-set obstacle); values are copies taken when read.")
        .def_property_readonly("name", [](const BoundaryView& b) { return b.boundary().name; })
        .def_property_readonly("shape",
                               [](const BoundaryView& b) { return shapeName(b.boundary().shape); },
                               "'plane', 'sphere', 'cylinder' or 'level-set'.")
        .def_property_readonly("reaction",
                               [](const BoundaryView& b) { return toArray(b.boundary().force); },
                               "(3,) the grains' force on it at the last evaluation.")
        .def_property_readonly(
            "displacement", [](const BoundaryView& b) { return toArray(b.boundary().displacement); },
            "(3,) how far it has moved.")
        .def_property_readonly("velocity",
                               [](const BoundaryView& b) { return toArray(b.boundary().velocity); },
                               "(3,) its prescribed velocity.")
        .def_property_readonly(
            "position", [](const BoundaryView& b) { return toArray(b.boundary().referencePoint()); },
            "(3,) its reference point now (plane point, sphere centre, obstacle centroid).")
        .def("__repr__", [](const BoundaryView& b) {
            return std::string("<lsdem.Boundary '") + b.boundary().name + "' (" +
                   shapeName(b.boundary().shape) + ")>";
        });

    py::class_<BoundariesView>(m, "Boundaries",
                               "The boundaries of a running simulation, by name: "
                               "sim.boundaries['top'].reaction.")
        .def("__len__", [](const BoundariesView& b) { return b.all().size(); })
        .def("__getitem__", &BoundariesView::at, py::arg("name"))
        .def("__contains__",
             [](const BoundariesView& b, const std::string& name) {
                 for (const Boundary& x : b.all())
                     if (x.name == name) return true;
                 return false;
             })
        .def("keys",
             [](const BoundariesView& b) {
                 std::vector<std::string> names;
                 for (const Boundary& x : b.all()) names.push_back(x.name);
                 return names;
             },
             "The boundary names, in scene order.")
        .def("__iter__", [](const BoundariesView& b) {
            return py::iter(py::cast(b).attr("keys")());
        });
}

} // namespace lsdem::python
