#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForcesOriginal(const std::vector<NodeContact>& contacts, double kn, double weight,
                          std::vector<PointForce>& out)
{
    for (const NodeContact& c : contacts)
        out.push_back({c.node, (weight * kn * c.depth) * c.normal, c.point, weight * kn});
}

} // namespace lsdem
