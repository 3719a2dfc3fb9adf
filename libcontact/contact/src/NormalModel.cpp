#include "lsdem/contact/NormalModel.h"

#include "NormalModels.h"

#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/core/Error.h"

namespace lsdem {

double NormalModel::elasticEnergy(const std::vector<NodeContact>& contacts, double stiffness,
                                  double weight) const
{
    const bool perArea = stiffnessPerArea();
    double sum = 0.0;
    for (const NodeContact& c : contacts)
        sum += nodeStiffness(perArea, stiffness, c.area) * c.depth * c.depth;
    return 0.5 * weight * sum;
}

double NormalModel::continuumSphereForce(double radius, double overlap, double traction) const
{
    return exactSphereContactForce(radius, overlap, traction);
}

namespace {

/// The registry: every formulation with its sub-model, in the order messages and studies list
/// them. A new law is its file (NormalModel<Name>.cpp), its Formulation value and its line here.
struct Registered
{
    Formulation formulation;
    const NormalModel& (*model)();
};

const std::vector<Registered>& registry()
{
    static const std::vector<Registered> all = {
        {Formulation::Original, normal_models::original},
        {Formulation::Adapted, normal_models::adapted},
        {Formulation::SingleNode, normal_models::singleNode},
        {Formulation::Volume, normal_models::volume},
    };
    return all;
}

} // namespace

const NormalModel& normalModel(Formulation formulation)
{
    for (const Registered& r : registry())
        if (r.formulation == formulation) return r.model();
    throw Error("", "unknown contact formulation (corrupt value)");
}

const std::vector<Formulation>& allFormulations()
{
    static const std::vector<Formulation> all = [] {
        std::vector<Formulation> v;
        for (const Registered& r : registry()) v.push_back(r.formulation);
        return v;
    }();
    return all;
}

std::string formulationNamesWhere(bool (NormalModel::*property)() const, const std::string& quote)
{
    std::vector<std::string> names;
    for (Formulation f : allFormulations())
        if ((normalModel(f).*property)()) names.push_back(quote + formulationName(f) + quote);
    std::string text;
    for (size_t i = 0; i < names.size(); ++i)
        text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return text;
}

std::string formulationName(Formulation f) { return normalModel(f).name(); }

Formulation parseFormulation(const std::string& name)
{
    std::string names;
    for (Formulation f : allFormulations()) {
        if (formulationName(f) == name) return f;
        names += (names.empty() ? "" : ", ") + formulationName(f);
    }
    throw Error("", "unknown contact formulation '" + name + "'", "use one of: " + names);
}

} // namespace lsdem
