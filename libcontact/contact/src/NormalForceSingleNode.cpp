#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForcesSingleNode(const std::vector<NodeContact>& contacts, double kn, double weight,
                            std::vector<PointForce>& out)
{
    if (contacts.empty()) return;
    const NodeContact* deepest = &contacts.front();
    for (const NodeContact& c : contacts)
        if (c.depth > deepest->depth) deepest = &c;  // first of equals: deterministic
    out.push_back({deepest->node, (weight * kn * deepest->depth) * deepest->normal,
                   deepest->point, weight * kn});
}

} // namespace lsdem
