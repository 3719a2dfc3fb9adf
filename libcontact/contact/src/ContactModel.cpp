#include "lsdem/contact/ContactModel.h"

#include "lsdem/core/Error.h"

namespace lsdem {

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

std::string stiffnessUnit(Formulation f) { return normalModel(f).stiffnessUnit(); }

} // namespace lsdem
