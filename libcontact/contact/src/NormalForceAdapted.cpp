#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForcesAdapted(const std::vector<NodeContact>& contacts, double knStar, double weight,
                         std::vector<PointForce>& out)
{
    // Traction kn*·d integrated with the node areas as quadrature weights.
    for (const NodeContact& c : contacts) {
        const double k = weight * knStar * c.area;
        out.push_back({c.node, (k * c.depth) * c.normal, c.point, k});
    }
}

} // namespace lsdem
