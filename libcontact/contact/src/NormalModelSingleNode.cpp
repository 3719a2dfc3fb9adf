// Single-node contact (Li et al. 2019; YADE's default level-set contact): one spring kn at the
// deepest penetrating node of the pair.
#include "NormalModels.h"

#include <algorithm>

namespace lsdem::normal_models {

namespace {

class SingleNode final : public NormalModel
{
public:
    Formulation formulation() const override { return Formulation::SingleNode; }
    std::string name() const override { return "single-node"; }
    std::string stiffnessUnit() const override { return "force/length"; }
    bool stiffnessPerArea() const override { return false; }
    bool perNodeForces() const override { return false; }
    double paperStiffness() const override { return 1e9; }
    double patchStiffness(double kn, double, double) const override { return kn; }
    // One spring, however large the contact: no traction it acts like.
    std::optional<double> tractionStiffness(double, double) const override { return {}; }
    std::optional<double> stiffnessForTraction(double, double) const override { return {}; }

    void forces(const std::vector<NodeContact>& contacts, double kn, double weight,
                std::vector<PointForce>& out) const override
    {
        if (contacts.empty()) return;
        const NodeContact* deepest = &contacts.front();
        for (const NodeContact& c : contacts)
            if (c.depth > deepest->depth) deepest = &c;  // first of equals: deterministic
        out.push_back({deepest->node, (weight * kn * deepest->depth) * deepest->normal,
                       deepest->point, weight * kn});
    }

    /// One spring of the deepest node.
    double elasticEnergy(const std::vector<NodeContact>& contacts, double kn,
                         double weight) const override
    {
        double deepest = 0.0;
        for (const NodeContact& c : contacts) deepest = std::max(deepest, c.depth);
        return 0.5 * weight * kn * deepest * deepest;
    }
};

} // namespace

const NormalModel& singleNode()
{
    static const SingleNode model;
    return model;
}

} // namespace lsdem::normal_models
