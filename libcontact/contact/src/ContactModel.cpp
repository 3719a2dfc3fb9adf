#include "lsdem/contact/ContactModel.h"

#include "lsdem/ls/Constants.h"
#include "lsdem/ls/Error.h"

#include <cmath>

namespace lsdem {

std::string formulationName(Formulation f)
{
    switch (f) {
    case Formulation::Original: return "original";
    case Formulation::Adapted: return "adapted";
    case Formulation::SingleNode: return "single-node";
    case Formulation::Volume: return "volume";
    }
    return "?";
}

Formulation parseFormulation(const std::string& name)
{
    for (Formulation f : {Formulation::Original, Formulation::Adapted, Formulation::SingleNode,
                          Formulation::Volume})
        if (formulationName(f) == name) return f;
    throw Error("", "unknown contact formulation '" + name + "'",
                "use one of: original, adapted, single-node, volume");
}

std::string nodeTestingName(NodeTesting t)
{
    return t == NodeTesting::OneWay ? "one-way" : "symmetric";
}

NodeTesting parseNodeTesting(const std::string& name)
{
    if (name == "one-way") return NodeTesting::OneWay;
    if (name == "symmetric") return NodeTesting::Symmetric;
    throw Error("", "unknown node testing '" + name + "'", "use one-way or symmetric");
}

double dampingRatioFromRestitution(double restitution)
{
    const double logE = std::log(restitution);
    return -logE / std::sqrt(kPi * kPi + logE * logE);
}

std::string stiffnessUnit(Formulation f)
{
    switch (f) {
    case Formulation::Original:
    case Formulation::SingleNode: return "force/length";
    case Formulation::Adapted: return "force/length^3 (traction per penetration)";
    case Formulation::Volume: return "force/length^3 (force per overlap volume)";
    }
    return "?";
}

} // namespace lsdem
