// sim.membranes in Python: a running simulation's membranes, their vertices, triangles and
// what they enclose, as copies taken when read.
#include "PySimulation.h"

#include "lsdem/simulation/Membrane.h"

#include <pybind11/stl.h>

namespace lsdem::python {

namespace {

py::array_t<double> vectorsOf(const std::vector<Vec3>& v)
{
    py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
    auto o = out.mutable_unchecked<2>();
    for (size_t i = 0; i < v.size(); ++i)
        for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = v[i][k];
    return out;
}

} // namespace

void bindMembraneViews(py::module_& m)
{
    py::class_<MembraneView>(m, "Membrane",
                             "One membrane of a running simulation; values are copies taken "
                             "when read.")
        .def_property_readonly("name", [](const MembraneView& v) { return v.membrane().name; })
        .def_property_readonly(
            "positions", [](const MembraneView& v) { return vectorsOf(v.membrane().positions); },
            "(V, 3) its vertices now (length).")
        .def_property_readonly(
            "velocities", [](const MembraneView& v) { return vectorsOf(v.membrane().velocities); },
            "(V, 3) its vertices' velocities.")
        .def_property_readonly(
            "grain_forces",
            [](const MembraneView& v) { return vectorsOf(v.membrane().grainForces); },
            "(V, 3) the grains' push on each vertex at the last evaluation.")
        .def_property_readonly(
            "triangles",
            [](const MembraneView& v) {
                const std::vector<MembraneTriangle>& t = v.membrane().triangles;
                py::array_t<int> out({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
                auto o = out.mutable_unchecked<2>();
                for (size_t i = 0; i < t.size(); ++i)
                    for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = t[i].vertices[size_t(k)];
                return out;
            },
            "(T, 3) int: each triangle's vertices, counter-clockwise seen from outside.")
        .def_property_readonly("held_by",
                               [](const MembraneView& v) { return v.membrane().heldBy; },
                               "Per vertex: the index of the boundary holding it, or -1.")
        .def_property_readonly("pressure", [](const MembraneView& v) { return v.membrane().pressure; },
                               "The pressure on its outer side (force/area).")
        .def_property_readonly(
            "volume", [](const MembraneView& v) { return enclosedVolume(v.membrane()); },
            "The volume it encloses, its rims closed by flat fans (length³).")
        .def_property_readonly("strain_energy",
                               [](const MembraneView& v) { return v.membrane().strainEnergy; },
                               "Its rubber's elastic energy at the last evaluation.")
        .def("__repr__", [](const MembraneView& v) {
            return "<lsdem.Membrane '" + v.membrane().name + "' (" +
                   std::to_string(v.membrane().positions.size()) + " vertices)>";
        });

    py::class_<MembranesView>(m, "Membranes",
                              "The membranes of a running simulation, by name: "
                              "sim.membranes['sleeve'].volume.")
        .def("__len__", [](const MembranesView& v) { return v.all().size(); })
        .def("__getitem__", &MembranesView::at, py::arg("name"))
        .def("__contains__",
             [](const MembranesView& v, const std::string& name) {
                 for (const Membrane& x : v.all())
                     if (x.name == name) return true;
                 return false;
             })
        .def("keys", [](const MembranesView& v) {
            std::vector<std::string> names;
            for (const Membrane& x : v.all()) names.push_back(x.name);
            return names;
        });
}

} // namespace lsdem::python
