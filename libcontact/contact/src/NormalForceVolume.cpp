#include "lsdem/contact/NormalForce.h"

namespace lsdem {

void normalForcesVolume(const std::vector<NodeContact>& contacts, double kv, double weight,
                        std::vector<PointForce>& out)
{
    // Riemann sum of the overlap volume over A's penetrating surface: V ≈ Σ d_a·A_a.
    double volume = 0.0, area = 0.0;
    Vec3 direction = Vec3::Zero(), centroid = Vec3::Zero();
    for (const NodeContact& c : contacts) {
        const double w = c.depth * c.area;
        volume += w;
        area += c.area;
        direction += w * c.normal;
        centroid += w * c.point;
    }
    if (volume <= 0.0 || direction.norm() == 0.0) return;
    // dV/dd = the penetrating area, so the stiffness is kv·Σ A_a.
    out.push_back({-1, (weight * kv * volume) * direction.normalized(), centroid / volume,
                   weight * kv * area});
}

} // namespace lsdem
