// Adapted (continuum) LS-DEM (Feldfogel et al. 2024): the nodes are quadrature points of the
// traction kn*·d, weighted by their tributary areas, so results converge with refinement.
#include "NormalModels.h"

namespace lsdem::normal_models {

namespace {

class Adapted final : public NormalModel
{
public:
    Formulation formulation() const override { return Formulation::Adapted; }
    std::string name() const override { return "adapted"; }
    std::string stiffnessUnit() const override
    {
        return "force/length^3 (traction per penetration)";
    }
    bool stiffnessPerArea() const override { return true; }
    bool perNodeForces() const override { return true; }
    double paperStiffness() const override { return 1e3; }
    double patchStiffness(double knStar, double area, double) const override
    {
        return knStar * area;
    }
    std::optional<double> tractionStiffness(double knStar, double) const override
    {
        return knStar;
    }
    std::optional<double> stiffnessForTraction(double traction, double) const override
    {
        return traction;
    }

    void forces(const std::vector<NodeContact>& contacts, double knStar, double weight,
                std::vector<PointForce>& out) const override
    {
        for (const NodeContact& c : contacts) {
            const double k = weight * knStar * c.area;
            out.push_back({c.node, (k * c.depth) * c.normal, c.point, k});
        }
    }
};

} // namespace

const NormalModel& adapted()
{
    static const Adapted model;
    return model;
}

} // namespace lsdem::normal_models
