// What the silo case will take (VerifyCases.h: siloDischargeSeconds): each kind of grain's
// packing, settling and discharges, from costs measured on this machine and the discharges'
// durations from Beverloo's law.
#include "studies/verify/BeverlooFit.h"
#include "studies/verify/SiloPlan.h"
#include "studies/verify/VerifyCases.h"

#include "lsdem/core/Constants.h"

#include <algorithm>
#include <cmath>

namespace lsdem::verify {

namespace {

/// What one kind of grain costs in the silo on 2 idle cores of this machine: measured
/// (docs/verification.md#cost), not derived, but for the discharges' durations, which
/// Beverloo's law gives.
struct KindCost
{
    double packing;        ///< s per grain^kPackingExponent to pack the fill
    double grainStep;      ///< s per grain and step, settling or flowing
    double timeStep;       ///< s: the automatic step at safety 0.2 under the silo's law
    double bulkDensity;    ///< t/mm³ of the settled fill
    double size;           ///< d, mm
    double annulus;        ///< Beverloo's k, grain sizes
    double bake;           ///< s to bake the kind's assets
};

/// Packing time grows faster than the grain count (each layer settles on those below it):
/// 8.3 s for the quick silo's 450 spheres, 220 s for the full one's 4300 (2026-11-29).
constexpr double kPackingExponent = 1.45;

KindCost kindCost(bool sand, bool quick)
{
    // Spheres: `verify --quick` (100 nodes: 0.84 to 0.96 µs a grain-step) and `verify --case
    // silo` with one orifice (200 nodes: 1.45 to 1.6 µs settling or flowing; 2.3 once, the
    // fastest flow), 2026-11-29, idle. Sand: the sessions that ran it (2026-11-28, 2 cores
    // shared with builds and tests): packed in 27 and over 50 min, 3.4 to 6.4 µs a grain-step:
    // its figures are the least sure.
    if (sand) return {1620.0 / std::pow(4300.0, kPackingExponent), 5.0e-6, 3.9e-6, 1.637e-9,
                      1.0275, 2.0, 3.0};
    if (quick) return {8.31 / std::pow(450.0, kPackingExponent), 0.9e-6, 6.11e-6, 1.401e-9, 1.0,
                       1.5, 0.0};
    return {220.0 / std::pow(4300.0, kPackingExponent), 1.5e-6, 1.066e-5, 1.532e-9, 1.0, 1.5,
            0.0};
}

/// Least and most seconds of one kind's packing, settling and discharges.
std::pair<double, double> kindSeconds(const SiloPlan& p, const KindCost& k)
{
    const double grains = double(p.grains);
    const double packing = k.packing * std::pow(grains, kPackingExponent);
    const double settle = p.settleTime / k.timeStep * grains * k.grainStep;
    double discharges = 0.0;
    const double grainMass = p.density * kPi / 6.0 * k.size * k.size * k.size;
    for (double d : p.orifices) {
        // Beverloo's flow at C = 0.58 (the measured durations were 0.83 to 1.19 times what it
        // gives). The grains stepped: the fill less those set aside once out, about half the
        // counted ones on average.
        const double annulus = std::min(k.annulus * k.size, d - 0.5 * k.size);
        const double flow = beverlooFlow(0.58, k.bulkDensity, p.gravity, d, annulus);
        const double duration = p.countTo * grainMass / flow;
        discharges += duration / k.timeStep * (grains - 0.5 * p.countTo) * k.grainStep;
    }
    // The packing's time is the least certain (±30 %); a fast flow cost up to 1.5 times the
    // settling's rate a grain-step once.
    const double sure = k.bake + settle;
    return {sure + 0.7 * packing + 0.85 * discharges, sure + 1.3 * packing + 1.3 * discharges};
}

} // namespace

std::pair<double, double> siloDischargeSeconds(const VerifyOptions& o)
{
    const SiloPlan p = planAsAsked(o.quick, o.siloRadius, o.siloHeight, o.siloOrifices);
    std::pair<double, double> seconds{0.0, 0.0};
    auto add = [&](const std::pair<double, double>& kind) {
        seconds.first += kind.first;
        seconds.second += kind.second;
    };
    if (wantsKind(o.siloGrains, "spheres")) add(kindSeconds(p, kindCost(false, o.quick)));
    if (wantsKind(o.siloGrains, "sand") && !o.quick) add(kindSeconds(p, kindCost(true, false)));
    return seconds;
}

} // namespace lsdem::verify
