#include "studies/SlabOptions.h"

#include "studies/FormulationList.h"
#include "studies/SlabCost.h"

#include "lsdem/core/NumberText.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace lsdem {

double slabDeltaMax(const SlabStudyOptions& o)
{
    // Twice the thickness: the central block is out well before (at about 1.6 t by default).
    return o.deltaMax > 0.0 ? o.deltaMax : 2.0 * o.panel.thickness;
}

namespace {

void requirePositive(double v, const std::string& option, const std::string& example)
{
    if (!(v > 0.0) || !std::isfinite(v))
        throw Error("", option + " must be positive and finite, got " + roundedText(v),
                    "e.g. " + option + " " + example);
}

void requireNonNegative(double v, const std::string& option)
{
    if (!(v >= 0.0) || !std::isfinite(v))
        throw Error("", option + " must be zero (default) or positive, got " + roundedText(v));
}

/// The blocks' material and the run's damping and gravity.
void checkSlabMaterial(const SlabMaterial& m)
{
    requirePositive(m.youngModulus, "--young", "7e4");
    if (!(m.poisson >= 0.0 && m.poisson < 0.5))
        throw Error("", "--poisson must be in [0, 0.5), got " + roundedText(m.poisson), "e.g. --poisson 0.22");
    requirePositive(m.density, "--density", "2.5e-9");
    requireNonNegative(m.friction, "--friction");
    if (!(m.restitution > 0.0 && m.restitution <= 1.0))
        throw Error("", "--restitution must be in (0, 1], got " + roundedText(m.restitution),
                    "1 means no contact damping");
    if (!(m.globalDamping >= 0.0 && m.globalDamping < 1.0))
        throw Error("", "--damping must be in [0, 1), got " + roundedText(m.globalDamping));
    requireNonNegative(m.gravity, "--gravity");
}

/// The contact stiffnesses, the indenter and its push, and the time step's safety.
void checkSlabLoading(const SlabStudyOptions& o)
{
    requireNonNegative(o.knStar, "--kn-star");
    requireNonNegative(o.ksStar, "--ks-star");
    requireNonNegative(o.knOriginal, "--kn");
    requireNonNegative(o.referenceSdp, "--reference-sdp");
    requirePositive(o.indenterRadius, "--indenter-radius", "2.5");
    requirePositive(o.speed, "--speed", "200");
    requireNonNegative(o.deltaMax, "--delta-max");
    if (slabDeltaMax(o) > 3.0 * o.panel.thickness)
        throw Error("", "--delta-max " + roundedText(slabDeltaMax(o)) + " is more than three block thicknesses",
                    "the central block is out long before; e.g. --delta-max " + roundedText(o.panel.thickness));
    // The step is set from the normal stiffness of a face; shear and rocking make a block
    // stiffer than that by up to about 1.4x (ks*/kn* = 0.41 by default), hence the cap.
    if (!(o.timeStepSafety > 0.0 && o.timeStepSafety <= 0.5))
        throw Error("", "--safety must be in (0, 0.5], got " + roundedText(o.timeStepSafety), "0.3 is the default");
}

/// The laws, and the two-way study's need of the adapted one.
void checkSlabFormulations(const SlabStudyOptions& o)
{
    checkFormulationList(o.formulations);
    if (o.twoWay && std::find(o.formulations.begin(), o.formulations.end(), Formulation::Adapted) ==
                        o.formulations.end())
        throw Error("", "the two-way study refines the adapted formulation, which --formulation leaves out",
                    "add adapted to --formulation, or give --no-two-way for curves only");
}

/// The node spacings and voxel sizes, each fine enough for the blocks' thickness.
void checkSlabResolutions(const SlabStudyOptions& o)
{
    if (o.sdps.empty()) throw Error("", "--sdp needs at least one node spacing");
    const double thinnest = o.panel.thickness;
    for (double s : o.sdps) {
        requirePositive(s, "--sdp", "0.5");
        if (s > 0.5 * thinnest)
            throw Error("", "--sdp " + roundedText(s) + " mm leaves fewer than two node spacings across the " +
                                roundedText(thinnest) + " mm thickness",
                        "use node spacings below " + roundedText(0.5 * thinnest) + " mm");
    }
    for (double s : o.originalSdps) {
        requirePositive(s, "--sdp-original", "0.5");
        if (std::none_of(o.sdps.begin(), o.sdps.end(),
                         [&](double t) { return std::abs(t - s) <= 1e-12 * s; }))
            throw Error("", "--sdp-original " + roundedText(s) + " is not one of the --sdp values",
                        "the original formulation runs at a subset of --sdp; list it there too");
    }
    auto checkVoxel = [&](double v, const std::string& option) {
        requirePositive(v, option, "0.15");
        if (v * 4.0 > thinnest)
            throw Error("", option + " " + roundedText(v) + " mm leaves fewer than 4 voxels across the " +
                                roundedText(thinnest) + " mm thickness",
                        "use voxels of at most " + roundedText(thinnest / 4.0) + " mm");
    };
    checkVoxel(o.fixedVdp, "--vdp-fixed");
    if (o.twoWay) {
        if (o.vdps.empty()) throw Error("", "--vdp needs at least one voxel size");
        for (double v : o.vdps) checkVoxel(v, "--vdp");
    }
}

/// What the study reports: the convergence tolerance, the snapshots, the curves' samples.
void checkSlabOutputs(const SlabStudyOptions& o)
{
    requirePositive(o.tolerance, "--tolerance", "0.05");
    for (double d : o.snapshotDeltas)
        if (!(d >= 0.0 && d <= slabDeltaMax(o)))
            throw Error("", "--snapshots " + roundedText(d) + " is outside [0, δ_max = " + roundedText(slabDeltaMax(o)) + "]",
                        "give snapshot displacements between 0 and --delta-max");
    if (o.samples < 10 || o.samples > 100000) throw Error("", "--samples must be 10 to 100000");
}

/// Finite but absurd values (a crawling indenter, a feather-light block, microscopic voxels)
/// would run for years or exhaust memory: refuse them with the estimate.
void checkSlabCost(const SlabStudyOptions& o)
{
    const SlabCostEstimate cost = estimateSlabCost(o);
    if (cost.steps > kMaxSlabSteps)
        throw Error("", "the study would take " + roundedText(double(cost.steps)) + " time steps",
                    "check --speed, --density, --safety and the stiffnesses (the default is 1.6e5 steps)");
    if (cost.memoryBytes > kMaxSlabMemoryBytes)
        throw Error("", "the study would need about " + roundedText(cost.memoryBytes / 1073741824.0) +
                            " GiB of memory (the budget is " + roundedText(kMaxSlabMemoryBytes / 1073741824.0) +
                            " GiB)",
                    "use coarser --vdp / --vdp-fixed or --sdp");
}

} // namespace

// The checks in groups (in their old order, so the first problem found is still the one
// reported); the cost last, once every value it reads is sane.
void checkSlabStudyOptions(const SlabStudyOptions& o)
{
    checkSlabPanelOptions(o.panel);
    checkSlabMaterial(o.material);
    checkSlabLoading(o);
    checkSlabFormulations(o);
    checkSlabResolutions(o);
    checkSlabOutputs(o);
    checkSlabCost(o);
}

SlabStudyOptions slabFullOptions()
{
    SlabStudyOptions o;
    o.sdps = {1.0, 0.7, 0.5, 0.35, 0.25, 0.18, 0.125};
    o.originalSdps = {1.0, 0.7, 0.5, 0.35, 0.25};
    o.fixedVdp = 0.035;
    o.vdps = {0.4, 0.28, 0.2, 0.14, 0.1, 0.07, 0.05, 0.035};
    return o;
}

SlabStudyOptions slabSeedOptions()
{
    SlabStudyOptions o;
    o.formulations = {Formulation::Adapted};
    o.sdps = {1.0, 0.7, 0.5, 0.35, 0.25, 0.18, 0.125, 0.09, 0.06};
    o.originalSdps.clear();
    o.fixedVdp = 0.025;
    o.vdps = {0.4, 0.28, 0.2, 0.14, 0.1, 0.07, 0.05, 0.035, 0.025};
    return o;
}

std::vector<double> slabCoarseToFine(std::vector<double> v)
{
    std::sort(v.begin(), v.end(), std::greater<double>());
    v.erase(std::unique(v.begin(), v.end(), [](double a, double b) {
                return std::abs(a - b) <= 1e-12 * std::max(a, b);
            }),
            v.end());
    return v;
}

bool slabStageOneRuns(const SlabStudyOptions& o, Formulation f, double sdp)
{
    if (normalModel(f).stiffnessPerArea() || o.originalSdps.empty()) return true;
    for (double s : o.originalSdps)
        if (std::abs(s - sdp) <= 1e-12 * sdp) return true;
    return false;
}

std::vector<double> slabSnapshotDeltas(const SlabStudyOptions& o)
{
    if (!o.snapshotDeltas.empty()) {
        std::vector<double> d = o.snapshotDeltas;
        std::sort(d.begin(), d.end());
        return d;
    }
    std::vector<double> d;
    for (int k = 0; k <= 5; ++k) d.push_back(slabDeltaMax(o) * k / 5.0);
    return d;
}

} // namespace lsdem
