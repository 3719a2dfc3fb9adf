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

const NormalModel& normalModel(Formulation formulation)
{
    switch (formulation) {
    case Formulation::Original: return normal_models::original();
    case Formulation::Adapted: return normal_models::adapted();
    case Formulation::SingleNode: return normal_models::singleNode();
    case Formulation::Volume: return normal_models::volume();
    }
    throw Error("", "unknown contact formulation (corrupt value)");
}

const std::vector<Formulation>& allFormulations()
{
    static const std::vector<Formulation> all = {Formulation::Original, Formulation::Adapted,
                                                 Formulation::SingleNode, Formulation::Volume};
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
