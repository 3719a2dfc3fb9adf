// Scene builder methods in Python: assets, materials, contact laws (checked by the contact
// library's schema, as the scene reader checks [[contacts]]) and grains, one by one.
#include "SceneBuilding.h"

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/GrainKeys.h"

#include "lsdem/contact/ContactCoefficients.h"
#include "lsdem/core/Error.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace lsdem::python {

namespace fs = std::filesystem;

// Long by nature: one .def per builder method, each with its keyword arguments and docstring.
void bindSceneContents(py::class_<Scene>& scene)
{
    scene
        .def("add_asset",
             [](Scene& s, const std::string& name, const AssetHandle& asset) {
                 checkNewName(s.assets, name, "asset");
                 markChanged(s);
                 AssetSpec spec;
                 spec.name = name;
                 spec.loaded = asset.asset;
                 if (!asset.path.empty()) spec.file = fs::absolute(asset.path).string();
                 spec.where = "asset '" + name + "'";
                 s.assets.push_back(spec);
             },
             py::arg("name"), py::arg("asset"),
             "Use an Asset (baked or loaded in Python) under this name. to_toml writes the "
             "file it was loaded from or saved to.")
        .def("add_material",
             [](Scene& s, const std::string& name, double density) {
                 checkNewName(s.materials, name, "material");
                 if (std::optional<std::string> p = densityProblem(density))
                     throw Error("", "material '" + name + "': density " + *p, kDensityFix);
                 markChanged(s);
                 s.materials.push_back({name, density});
             },
             py::arg("name"), py::arg("density") = 0.0,
             "A material: density in mass/length³ (> 0 for free grains; boundaries need none).")
        .def("add_contact",
             [](Scene& s, const std::string& a, const std::string& b,
                const std::string& formulation, double normalStiffness, double shearStiffness,
                double friction, double restitution, const std::string& testing,
                const std::string& quadrature) {
                 ContactSpec c;
                 c.materialA = indexOf(s.materials, a, "material");
                 c.materialB = indexOf(s.materials, b, "material");
                 for (const ContactSpec& other : s.contacts)
                     if (std::minmax(other.materialA, other.materialB) ==
                         std::minmax(c.materialA, c.materialB))
                         throw Error("", "there is already a contact law between materials '" +
                                             a + "' and '" + b + "'",
                                     "give each pair of materials one law");
                 // The contact library's schema sets the words and checks the numbers, as the
                 // scene reader does.
                 const std::pair<const char*, const std::string*> words[] = {
                     {"formulation", &formulation}, {"testing", &testing},
                     {"quadrature", &quadrature}};
                 for (const auto& [key, value] : words) contactChoice(key).set(c.model, *value);
                 const std::pair<const char*, double> given[] = {
                     {"normal_stiffness", normalStiffness}, {"shear_stiffness", shearStiffness},
                     {"friction", friction}, {"restitution", restitution}};
                 for (const auto& [key, value] : given) {
                     const ContactCoefficient& k = contactCoefficient(key);
                     if (std::optional<ContactProblem> p = k.rangeProblem(value))
                         throw Error("", p->key + " " + p->problem, p->fix);
                     k.set(c.model, value);
                 }
                 if (std::optional<ContactProblem> p = checkContactModel(c.model, "'"))
                     throw Error("", p->key + " " + p->problem, p->fix);
                 markChanged(s);
                 c.where = "contact " + a + "-" + b;
                 s.contacts.push_back(c);
             },
             py::arg("material_a"), py::arg("material_b"), py::kw_only(),
             py::arg("formulation") = contactChoice("formulation").defaultValue(),
             py::arg("normal_stiffness"),
             py::arg("shear_stiffness") = contactCoefficientDefault("shear_stiffness"),
             py::arg("friction") = contactCoefficientDefault("friction"),
             py::arg("restitution") = contactCoefficientDefault("restitution"),
             py::arg("testing") = contactChoice("testing").defaultValue(),
             py::arg("quadrature") = contactChoice("quadrature").defaultValue(),
             "The contact law between two materials: formulation ('adapted', 'original', "
             "'single-node', 'volume'), normal_stiffness (kn or kn*, see docs/contact.md), "
             "shear springs, friction, restitution in (0, 1] (1: no damping), node testing "
             "('symmetric' or 'one-way') and quadrature ('node', or 'patch': each node "
             "integrated over its patch, for contacts narrower than the node spacing).")
        .def("add_grain",
             [](Scene& s, const std::string& asset, const std::string& material,
                const py::object& position, const py::object& orientation,
                const py::object& velocity, const py::object& angularVelocity, double mass,
                const std::string& motion, const std::string& name) {
                 GrainKeys k;
                 k.name = name;
                 k.asset = indexOf(s.assets, asset, "asset");
                 k.material = indexOf(s.materials, material, "material");
                 k.position = toVec3(position, "position");
                 k.orientation = toQuat(orientation);
                 k.velocity = toVec3(velocity, "velocity");
                 k.angularVelocity = toVec3(angularVelocity, "angular_velocity");
                 k.mass = mass;
                 k.motion = motion;
                 GrainSpec g;
                 g.where = "grain " + std::to_string(s.grains.size());
                 if (std::optional<KeyProblem> p = applyGrainKeys(k, g))
                     throw Error("", g.where + ": " + keyProblemText(*p), p->fix);
                 if (!name.empty()) checkNewName(s.grains, name, "grain");
                 markChanged(s);
                 s.grains.push_back(g);
                 return s.grains.size() - 1;
             },
             py::arg("asset"), py::arg("material"), py::arg("position"), py::kw_only(),
             py::arg("orientation") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
             py::arg("velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("angular_velocity") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("mass") = 0.0, py::arg("motion") = "free", py::arg("name") = "",
             "Place a grain of a named asset and material: position of its centroid, "
             "orientation as a unit quaternion [w, x, y, z] (asset frame to world), initial "
             "velocity and angular velocity (world), mass (> 0 overrides density × volume), "
             "motion ('free', 'fixed', 'prescribed'). Returns its index.");
}

} // namespace lsdem::python
