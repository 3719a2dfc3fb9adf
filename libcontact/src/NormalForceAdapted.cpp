#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForcesAdapted(const std::vector<NodeContact>& contacts, double knStar, double weight,
                         std::vector<PointForce>& out)
{
    // Traction kn*·d integrated with the node areas as quadrature weights.
    for (const NodeContact& c : contacts)
        out.push_back({c.node, (weight * knStar * c.depth * c.area) * c.normal, c.point});
}

} // namespace lsdem
