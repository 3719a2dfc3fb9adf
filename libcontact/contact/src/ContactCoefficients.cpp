#include "lsdem/contact/ContactCoefficients.h"

#include "lsdem/core/NumberText.h"

#include <cmath>
#include <stdexcept>

namespace lsdem {

namespace {

/// The normal law's coefficient: its stiffness, in the unit the formulation gives it.
ContactCoefficient normalStiffness()
{
    return {"normal_stiffness", "normal", NumberRange::Positive, std::nullopt,
            [](const ContactModel& m) { return m.normalStiffness; },
            [](ContactModel& m, double v) { m.normalStiffness = v; },
            [](const ContactModel& m) { return m.normal().stiffnessUnit(); }};
}

/// The shear springs' coefficients (TangentialModel.h): their stiffness, by the normal law's
/// rule, and Coulomb's μ that caps them.
std::vector<ContactCoefficient> tangential()
{
    return {{"shear_stiffness", "tangential", NumberRange::NonNegative, 0.0,
             [](const ContactModel& m) { return m.shearStiffness; },
             [](ContactModel& m, double v) { m.shearStiffness = v; }},
            {"friction", "tangential", NumberRange::NonNegative, 0.0,
             [](const ContactModel& m) { return m.friction; },
             [](ContactModel& m, double v) { m.friction = v; }}};
}

/// The dashpot's coefficient (DampingModel.h): the restitution it is calibrated for.
ContactCoefficient restitution()
{
    return {"restitution", "damping", NumberRange::PositiveFraction, 1.0,
            [](const ContactModel& m) { return m.damping.restitution(); },
            [](ContactModel& m, double v) { m.damping = ViscousDamping(v); }};
}

/// The shear springs' rules beside the normal law of @a m.
std::optional<ContactProblem> tangentialProblem(const ContactModel& m, const std::string& quote)
{
    const bool perNode = m.normal().perNodeForces();
    const std::string perNodeLaws = formulationNamesWhere(&NormalModel::perNodeForces, quote);
    const std::string law = quote + formulationName(m.formulation) + quote;
    if (m.shearStiffness > 0.0 && !perNode)
        return ContactProblem{"shear_stiffness", "has no effect with formulation " + law,
                              "use " + perNodeLaws + " for tangential forces, or remove it"};
    // Friction bounds the shear springs' force: without them the contact is frictionless.
    if (m.friction > 0.0 && !perNode)
        return ContactProblem{"friction", "has no effect with formulation " + law,
                              "use " + perNodeLaws +
                                  " with a shear_stiffness for tangential forces, or remove it"};
    if (m.friction > 0.0 && !(m.shearStiffness > 0.0))
        return ContactProblem{"friction", "has no effect without shear springs (shear_stiffness is 0)",
                              "give shear_stiffness > 0 (ks* or ks, see docs/contact.md), or "
                              "remove friction"};
    return std::nullopt;
}

} // namespace

std::string ContactCoefficient::rangeText() const
{
    return numberRangeText(range);
}

std::optional<ContactProblem> ContactCoefficient::rangeProblem(double value) const
{
    const std::optional<std::string> problem = outOfRange(range, value);
    if (!problem) return std::nullopt;
    return ContactProblem{key, *problem,
                          range == NumberRange::PositiveFraction ? "1 means no contact damping"
                                                                 : "give a value " + rangeText()};
}

bool ContactCoefficient::written(const ContactModel& model) const
{
    return !defaultValue || get(model) != *defaultValue;
}

const std::vector<ContactChoice>& contactChoices()
{
    static const std::vector<ContactChoice> all = [] {
        std::vector<std::string> formulations;
        for (Formulation f : allFormulations()) formulations.push_back(formulationName(f));
        return std::vector<ContactChoice>{
            {"formulation", formulations,
             [](const ContactModel& m) { return formulationName(m.formulation); },
             [](ContactModel& m, const std::string& v) { m.formulation = parseFormulation(v); }},
            {"testing", {nodeTestingName(NodeTesting::OneWay), nodeTestingName(NodeTesting::Symmetric)},
             [](const ContactModel& m) { return nodeTestingName(m.testing); },
             [](ContactModel& m, const std::string& v) { m.testing = parseNodeTesting(v); }},
            {"quadrature",
             {nodeQuadratureName(NodeQuadrature::Point), nodeQuadratureName(NodeQuadrature::Patch)},
             [](const ContactModel& m) { return nodeQuadratureName(m.quadrature); },
             [](ContactModel& m, const std::string& v) { m.quadrature = parseNodeQuadrature(v); },
             false}};
    }();
    return all;
}

const ContactChoice& contactChoice(const std::string& key)
{
    for (const ContactChoice& c : contactChoices())
        if (c.key == key) return c;
    throw std::out_of_range("no contact choice named " + key);
}

const std::vector<ContactCoefficient>& contactCoefficients()
{
    static const std::vector<ContactCoefficient> all = [] {
        std::vector<ContactCoefficient> v = {normalStiffness()};
        for (const ContactCoefficient& c : tangential()) v.push_back(c);
        v.push_back(restitution());
        return v;
    }();
    return all;
}

const ContactCoefficient& contactCoefficient(const std::string& key)
{
    for (const ContactCoefficient& c : contactCoefficients())
        if (c.key == key) return c;
    throw std::out_of_range("no contact coefficient named " + key);
}

double contactCoefficientDefault(const std::string& key)
{
    const ContactCoefficient& c = contactCoefficient(key);
    if (!c.defaultValue) throw std::out_of_range("contact coefficient " + key + " has no default");
    return *c.defaultValue;
}

std::optional<ContactProblem> checkContactModel(const ContactModel& model, const std::string& quote)
{
    for (const ContactCoefficient& c : contactCoefficients())
        if (std::optional<ContactProblem> p = c.rangeProblem(c.get(model))) return p;
    if (std::optional<ContactProblem> p = tangentialProblem(model, quote)) return p;
    if (model.quadrature == NodeQuadrature::Patch && !model.normal().integratesPatches())
        return ContactProblem{
            "quadrature",
            "'patch' needs a law with a traction per area and a force per node, not formulation " +
                quote + formulationName(model.formulation) + quote,
            "use " + formulationNamesWhere(&NormalModel::integratesPatches, quote) +
                ", or quadrature = " + quote + "node" + quote};
    return std::nullopt;
}

} // namespace lsdem
