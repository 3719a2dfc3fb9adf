// Scene.add_membrane in Python: a tube of rubber round the grains, checked by the rules the
// scene reader applies to [[membranes]] (MembraneKeys.h).
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/MembraneKeys.h"

#include <pybind11/stl.h>

namespace lsdem::python {

void bindSceneMembranes(py::class_<Scene>& scene)
{
    scene.def(
        "add_membrane",
        [](Scene& s, const std::string& name, const std::string& material, double youngs,
           double poisson, double thickness, double density, const py::object& base,
           double radius, double height, int segments, int rings, const py::object& axis,
           double pressure, double drag, double prestretch, const std::vector<std::string>& hold,
           const std::string& state) {
            checkNewName(s.membranes, name, "membrane");
            MembraneSpec m;
            m.name = name;
            m.where = "membrane '" + name + "'";
            m.material = indexOf(s.materials, material, "material");
            m.rubber = MembraneMaterial{youngs, poisson, thickness, density};
            m.base = toVec3(base, "base");
            m.axis = toVec3(axis, "axis");
            m.radius = radius, m.height = height;
            m.segments = segments, m.rings = rings;
            m.pressure = pressure, m.drag = drag, m.prestretch = prestretch;
            for (const std::string& b : hold) m.hold.push_back(indexOf(s.boundaries, b, "boundary"));
            if (!state.empty()) m.state = scenePath(s, state);  // as a file names it
            if (std::optional<KeyProblem> p = membraneProblem(m))
                throw Error("", "membrane '" + name + "': " + keyProblemText(*p), p->fix);
            s.membranes.push_back(m);
            markChanged(s);
        },
        py::arg("name"), py::arg("material"), py::kw_only(), py::arg("youngs"),
        py::arg("poisson"), py::arg("thickness"), py::arg("density"), py::arg("base"),
        py::arg("radius"), py::arg("height"), py::arg("segments"), py::arg("rings"),
        py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0), py::arg("pressure") = 0.0,
        py::arg("drag") = 0.0, py::arg("prestretch") = 1.0,
        py::arg("hold") = std::vector<std::string>{}, py::arg("state") = std::string(),
        "A rubber tube round the grains (docs/scenes.md#membranes): its axis from `base` along "
        "`axis`, `radius` and `height` as placed, `segments` vertices round each of `rings` + 1 "
        "rings, stretched round by `prestretch` (>= 1); `pressure` pushes in on its outer side, "
        "`drag` is the cell fluid's; each rim is held by the nearest of the plane boundaries "
        "named in `hold`; `state`, a CSV file of x, y, z, vx, vy, vz per vertex (as a run left "
        "it), places its vertices, the tube keys then giving its rubber's unstretched shape. "
        "Grains meet it through the contact law with `material`.");
}

} // namespace lsdem::python
