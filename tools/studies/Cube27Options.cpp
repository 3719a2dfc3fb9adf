#include "studies/Cube27Options.h"

#include "lsdem/core/Error.h"

#include <cmath>
#include <string>

namespace lsdem {

Cube27Options cube27FullOptions()
{
    Cube27Options o;
    o.nodeCounts = {500, 1000, 2000, 4000, 8000, 16000};
    o.orientations = 3;
    o.voxel = 0.05;
    return o;
}

void checkCube27Options(const Cube27Options& o)
{
    checkSphereSeriesOptions(o);
    auto positive = [](double v, const std::string& option, const std::string& example) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw Error("", option + " must be positive and finite", "e.g. " + option + " " + example);
    };
    if (o.deltaMax >= 0.5 * o.radius)
        throw Error("", "--delta-max must be smaller than half the radius",
                    "the closed form and the stack assume small overlaps; e.g. --delta-max 0.3");
    if (o.voxel > 0.25 * o.radius)
        throw Error("", "--voxel is too coarse for the radius (more than R/4)", "e.g. --voxel 0.1");
    if (o.speed < 0.0 || !std::isfinite(o.speed))
        throw Error("", "--speed must be positive (or 0 for the automatic speed)", "e.g. --speed 20");
    if (o.steps < 0 || o.steps > 100000000)
        throw Error("", "--steps must be 1 to 1e8 (or 0 for the automatic count)");
    positive(o.periods, "--periods", "30");
    if (!(o.safety > 0.0 && o.safety <= 1.0))
        throw Error("", "--safety must be in (0, 1]", "e.g. --safety 0.2");
    if (o.points < 1 || o.points > 100000) throw Error("", "--points must be 1 to 100000");
    positive(o.density, "density", "7.85e-9");
    if (o.friction < 0.0 || !std::isfinite(o.friction)) throw Error("", "--friction must be >= 0");
    if (o.shearRatio < 0.0 || !std::isfinite(o.shearRatio))
        throw Error("", "the shear ratio ks/kn must be >= 0 (set in code: cube27 has no option for it)");
    if (!(o.restitution > 0.0 && o.restitution <= 1.0))
        throw Error("", "--restitution must be in (0, 1]", "e.g. --restitution 0.5");
    if (!(o.globalDamping >= 0.0 && o.globalDamping < 1.0))
        throw Error("", "--damping must be in [0, 1)", "e.g. --damping 0.3");
}

} // namespace lsdem
