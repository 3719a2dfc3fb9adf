#include "studies/verify/SiloPlan.h"

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

namespace {

/// The quick or full version's plan (the orifices 4 and 5 mm or 5 … 8 mm).
SiloPlan planFor(bool quick)
{
    SiloPlan p;
    if (quick) {
        p.siloRadius = 4.0;
        p.fillHeight = 8.0;
        p.orifices = {4.0, 5.0};
        p.grains = 450;
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
