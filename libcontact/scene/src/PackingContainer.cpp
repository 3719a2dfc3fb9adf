// The packing's container and the check of its options (PackingContainer.h).
#include "PackingContainer.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <cmath>
#include <sstream>

namespace lsdem {

Vec3 containerMin(const PackingOptions& o)
{
    if (!o.cylinder) return o.boxMin;
    const PackingCylinder& c = *o.cylinder;
    return Vec3(c.x - c.radius, c.y - c.radius, c.zMin);
}

Vec3 containerMax(const PackingOptions& o)
{
    if (!o.cylinder) return o.boxMax;
    const PackingCylinder& c = *o.cylinder;
    return Vec3(c.x + c.radius, c.y + c.radius, c.zMax);
}

double containerVolume(const PackingOptions& o)
{
    if (!o.cylinder) return (o.boxMax - o.boxMin).prod();
    const PackingCylinder& c = *o.cylinder;
    return kPi * c.radius * c.radius * (c.zMax - c.zMin);
}

void checkPackingOptions(const PackingOptions& o)
{
    if (o.mixture.empty())
        throw Error("", "no grain assets to pack", "give at least one asset");
    double total = 0.0;
    for (const PackingComponent& c : o.mixture) {
        if (!c.asset) throw Error("", "asset '" + c.name + "' is not loaded");
        if (!(c.fraction >= 0.0) || !std::isfinite(c.fraction))
            throw Error("", "the fraction of '" + c.name + "' must be a number >= 0",
                        "give fractions such as 0.7 0.3");
        total += c.fraction;
    }
    if (!(total > 0.0)) throw Error("", "the fractions add up to 0", "give a positive fraction");
    if (o.cylinder) {
        const PackingCylinder& c = *o.cylinder;
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !(c.radius > 0.0) ||
            !std::isfinite(c.radius) || !(c.zMax > c.zMin) || !std::isfinite(c.zMin) ||
            !std::isfinite(c.zMax))
            throw Error("", "the cylinder is empty (its radius must be > 0 and Z1 > Z0)",
                        "give --cylinder CX CY RADIUS Z0 Z1 with RADIUS > 0 and Z1 > Z0");
    } else if (!((o.boxMax - o.boxMin).minCoeff() > 0.0) || !o.boxMin.allFinite() ||
               !o.boxMax.allFinite()) {
        throw Error("", "the box is empty (its max corner must exceed its min corner)",
                    "give --box X0 Y0 Z0 X1 Y1 Z1 with X1 > X0, Y1 > Y0, Z1 > Z0");
    }
    // A negative friction used to pack as frictionless, and a tolerance <= 0 is never met, so
    // every layer ran to maxStepsPerLayer.
    if (!(o.friction >= 0.0) || !std::isfinite(o.friction))
        throw Error("", "--friction must be a finite number >= 0, got " + numberText(o.friction),
                    "give --friction 0 (the densest packing) or a Coulomb coefficient such as 0.5");
    if (!(o.settleTolerance > 0.0) || !std::isfinite(o.settleTolerance))
        throw Error("", "--settle must be a finite number > 0, got " +
                            numberText(o.settleTolerance),
                    "give a small fraction such as --settle 1e-5 (the default)");
    if (o.count < 1) throw Error("", "the grain count must be >= 1", "give --count N");
    if (o.count > 1000000)  // a scene's limit (SceneSections.h): checked before any memory is taken
        throw Error("", "the grain count " + std::to_string(o.count) +
                            " is over the limit of a scene (1000000)", "split the packing");
    const Vec3 size = containerMax(o) - containerMin(o);
    for (const PackingComponent& c : o.mixture) {
        const double d = 2.0 * c.asset->boundingRadius;
        if (c.fraction > 0.0 && d >= size.minCoeff()) {
            std::ostringstream s;
            s << "grain '" << c.name << "' (bounding diameter " << d
              << ") does not fit in the " << (o.cylinder ? "cylinder" : "box");
            throw Error("", s.str(), o.cylinder ? "enlarge the cylinder" : "enlarge the box");
        }
    }
}

} // namespace lsdem
