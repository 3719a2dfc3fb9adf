// Volume-based contact (after van der Haven et al. 2023): a force kv·V along the mean normal,
// with the overlap volume V estimated gratis as the Riemann sum Σ d_a·A_a over the penetrating
// nodes.
#include "NormalModels.h"

#include "lsdem/contact/SphereContactReference.h"

namespace lsdem::normal_models {

namespace {

class Volume final : public NormalModel
{
public:
    Formulation formulation() const override { return Formulation::Volume; }
    std::string name() const override { return "volume"; }
    std::string stiffnessUnit() const override
    {
        return "force/length^3 (force per overlap volume)";
    }
    bool stiffnessPerArea() const override { return true; }
    bool perNodeForces() const override { return false; }
    double paperStiffness() const override { return 1e3; }
    double patchStiffness(double kv, double area, double) const override { return kv * area; }
    // kv·V with V = ∫ d dA: a traction kv·d along the mean normal.
    std::optional<double> tractionStiffness(double kv, double) const override { return kv; }
    std::optional<double> stiffnessForTraction(double traction, double) const override
    {
        return traction;
    }
    double continuumSphereForce(double radius, double overlap, double kv) const override
    {
        return exactSphereVolumeForce(radius, overlap, kv);
    }

    void forces(const std::vector<NodeContact>& contacts, double kv, double weight,
                std::vector<PointForce>& out) const override
    {
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
};

} // namespace

const NormalModel& volume()
{
    static const Volume model;
    return model;
}

} // namespace lsdem::normal_models
