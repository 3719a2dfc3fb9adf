// [[contacts]]: the contact law between two materials.
#include "SceneSections.h"

namespace lsdem::scenefile {

ContactSpec readContact(TableReader& t, const Scene& scene)
{
    ContactSpec c;
    c.where = t.where();
    const toml::node& m = t.node("materials");
    const toml::array* pair = m.as_array();
    if (!pair || pair->size() != 2 || !(*pair)[0].is_string() || !(*pair)[1].is_string())
        t.fail("materials", "expected two material names", "write materials = [\"steel\", \"wall\"]");
    int idx[2];
    for (int s = 0; s < 2; ++s) {
        const std::string name = (*pair)[static_cast<size_t>(s)].as_string()->get();
        idx[s] = indexByName(scene.materials, name);
        if (idx[s] < 0)
            t.fail("materials", "no material named '" + name + "'", "define [materials." + name + "]");
    }
    c.materialA = idx[0];
    c.materialB = idx[1];
    ContactModel& model = c.model;
    std::vector<std::string> formulations;
    for (Formulation f : allFormulations()) formulations.push_back(formulationName(f));
    model.formulation =
        parseFormulation(t.choice("formulation", formulations, formulationName(model.formulation)));
    model.testing = parseNodeTesting(
        t.choice("testing", {"one-way", "symmetric"}, nodeTestingName(model.testing)));
    model.normalStiffness = t.positive("normal_stiffness");
    model.shearStiffness = t.nonNegative("shear_stiffness", 0.0);
    model.friction = t.nonNegative("friction", 0.0);
    const bool shearSprings = model.normal().perNodeForces();
    if (model.shearStiffness > 0.0 && !shearSprings)
        t.fail("shear_stiffness", "has no effect with formulation " +
                                      formulationName(model.formulation),
               "use " + formulationNamesWhere(&NormalModel::perNodeForces) +
                   " for tangential forces, or remove it");
    // Friction bounds the shear springs' force: without them the contact is frictionless.
    if (model.friction > 0.0 && !shearSprings)
        t.fail("friction", "has no effect with formulation " + formulationName(model.formulation),
               "use " + formulationNamesWhere(&NormalModel::perNodeForces) +
                   " with a shear_stiffness for tangential forces, or remove it");
    if (model.friction > 0.0 && !(model.shearStiffness > 0.0))
        t.fail("friction", "has no effect without shear springs (shear_stiffness is 0)",
               "give shear_stiffness > 0 (ks* or ks, see docs/contact.md), or remove friction");
    const double restitution = t.number("restitution", 1.0);
    if (!(restitution > 0.0 && restitution <= 1.0))
        t.fail("restitution", "must be in (0, 1] (got " + TableReader::show(restitution) + ")",
               "1 means no contact damping");
    model.damping = ViscousDamping(restitution);
    t.rejectUnknownKeys();
    return c;
}

} // namespace lsdem::scenefile
