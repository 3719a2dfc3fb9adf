#include "studies/SphereSeriesOptions.h"

#include "studies/FormulationList.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

void checkSphereSeriesOptions(const SphereSeriesOptions& o)
{
    auto positive = [](double v, const std::string& option, const std::string& example) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw Error("", option + " must be positive and finite", "e.g. " + option + " " + example);
    };
    checkFormulationList(o.formulations);
    if (o.nodeCounts.empty()) throw Error("", "--nodes needs at least one count");
    for (size_t i = 0; i < o.nodeCounts.size(); ++i) {
        const int n = o.nodeCounts[i];
        if (n < 20 || n > 5000000)
            throw Error("", "--nodes " + std::to_string(n) + " is out of range",
                        "give node counts from 20 to 5e6");
        if (std::find(o.nodeCounts.begin(), o.nodeCounts.begin() + i, n) != o.nodeCounts.begin() + i)
            throw Error("", "--nodes lists " + std::to_string(n) + " twice",
                        "use --orientations for repeated runs");
    }
    if (o.kSeriesNodes <= 0) throw Error("", "--k-nodes must be positive", "e.g. --k-nodes 4000");
    for (double k : o.stiffness) positive(k, "--kn", "1e3");
    for (double f : o.stiffnessFactors) positive(f, "--k-factors", "0.5");
    positive(o.radius, "--radius", "5");
    positive(o.voxel, "--voxel", "0.1");
    positive(o.deltaMax, "--delta-max", "0.1");
    if (o.orientations < 1 || o.orientations > 1000)
        throw Error("", "--orientations must be 1 to 1000");
}

int stiffnessSeriesNodes(const SphereSeriesOptions& o)
{
    int closest = o.nodeCounts.front();
    for (int n : o.nodeCounts)
        if (std::abs(n - o.kSeriesNodes) < std::abs(closest - o.kSeriesNodes)) closest = n;
    return closest;
}

GrainAsset bakeSeriesSphere(const SphereSeriesOptions& o, int nodes, std::vector<std::string>& warnings)
{
    BakeOptions bake;
    bake.voxelSize = o.voxel;
    bake.nodePlacement = NodePlacement::Count;
    bake.nodeCount = nodes;
    return bakeAnalytic(AnalyticShape::sphere(o.radius), bake, warnings);
}

} // namespace lsdem
