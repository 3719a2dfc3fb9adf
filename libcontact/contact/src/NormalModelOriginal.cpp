// Original LS-DEM (Kawamoto et al. 2016): a spring kn per penetrating node, so a grain's
// stiffness grows with the number of nodes in contact.
#include "NormalModels.h"

namespace lsdem::normal_models {

namespace {

class Original final : public NormalModel
{
public:
    Formulation formulation() const override { return Formulation::Original; }
    std::string name() const override { return "original"; }
    std::string stiffnessUnit() const override { return "force/length"; }
    bool stiffnessPerArea() const override { return false; }
    bool perNodeForces() const override { return true; }
    double paperStiffness() const override { return 1e9; }
    double patchStiffness(double kn, double area, double nodeArea) const override
    {
        return kn * area / nodeArea;
    }
    std::optional<double> tractionStiffness(double kn, double nodeArea) const override
    {
        return kn / nodeArea;
    }
    std::optional<double> stiffnessForTraction(double traction, double nodeArea) const override
    {
        return traction * nodeArea;
    }

    void forces(const std::vector<NodeContact>& contacts, double kn, double weight,
                std::vector<PointForce>& out) const override
    {
        for (const NodeContact& c : contacts)
            out.push_back({c.node, (weight * kn * c.depth) * c.normal, c.point, weight * kn});
    }
};

} // namespace

const NormalModel& original()
{
    static const Original model;
    return model;
}

} // namespace lsdem::normal_models
