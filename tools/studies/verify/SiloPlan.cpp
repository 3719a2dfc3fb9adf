#include "studies/verify/SiloPlan.h"

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

namespace {

/// The quick or full version's plan (the orifices 5 and 6 mm or 5 … 8 mm). The quick one's
/// orifices are at least 5 grain sizes, where a silo rarely clogs: its checks judge every run,
/// so none may hang on whether an arch happens to form (at 4 grain sizes one formed in one of
/// two otherwise equal runs whose level sets differed by 1e-6 voxel).
SiloPlan planFor(bool quick)
{
    SiloPlan p;
    if (quick) {
        p.siloRadius = 5.0;
        p.fillHeight = 8.0;
        p.orifices = {5.0, 6.0};
        p.grains = 700;
        p.countFrom = 50;
        p.countTo = 200;
        p.settleTime = 0.02;
        p.frames = 0;
    } else {
        p.orifices = {5.0, 6.0, 7.0, 8.0};
        p.grains = 4300;
    }
    return p;
}

} // namespace

SiloPlan planAsAsked(bool quick, double siloRadius, double siloHeight,
                     const std::vector<double>& orifices)
{
    SiloPlan p = planFor(quick);
    // A wider or taller silo holds grains in proportion to its fill's volume.
    const double radius = siloRadius > 0.0 ? siloRadius : p.siloRadius;
    const double height = siloHeight > 0.0 ? siloHeight : p.fillHeight;
    p.grains = std::llround(double(p.grains) * (radius * radius * height) /
                            (p.siloRadius * p.siloRadius * p.fillHeight));
    p.siloRadius = radius;
    p.fillHeight = height;
    if (!orifices.empty()) {
        p.orifices = orifices;
        std::sort(p.orifices.begin(), p.orifices.end());
        p.orifices.erase(std::unique(p.orifices.begin(), p.orifices.end()), p.orifices.end());
    }
    return p;
}

bool wantsKind(const std::vector<std::string>& kinds, const char* kind)
{
    return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

} // namespace lsdem::verify
