#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForces(Formulation formulation, const std::vector<NodeContact>& contacts,
                  double stiffness, double weight, std::vector<PointForce>& out)
{
    switch (formulation) {
    case Formulation::Original: normalForcesOriginal(contacts, stiffness, weight, out); return;
    case Formulation::Adapted: normalForcesAdapted(contacts, stiffness, weight, out); return;
    case Formulation::SingleNode:
        normalForcesSingleNode(contacts, stiffness, weight, out);
        return;
    case Formulation::Volume: normalForcesVolume(contacts, stiffness, weight, out); return;
    }
}

} // namespace lsdem
