#include "studies/Cube27Plan.h"

#include "studies/Cube27ClosedForm.h"
#include "studies/StudyLimits.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lsdem {

namespace {

/// Contact stiffnesses of a column at top wall travel @a delta, from the continuum laws:
/// kWall (sphere against a plane) and kSphere (sphere against sphere), force/length.
struct ColumnStiffness
{
    double kWall = 0.0, kSphere = 0.0;
};

ColumnStiffness columnStiffness(Formulation f, double radius, double delta, double stiffness,
                                int nodes)
{
    ColumnStiffness c;
    const std::optional<double> traction =
        normalModel(f).tractionStiffness(stiffness, 4 * kPi * radius * radius / nodes);
    if (!traction) {
        // A law without a traction (single-node): one linear spring per contact (symmetric
        // testing: two half-weight deepest nodes).
        c.kWall = c.kSphere = stiffness;
        return c;
    }
    const double kStar = *traction;
    const double dWall = delta / kCube27Column, dSphere = std::sqrt(2.0) * dWall;
    c.kWall = 2 * kPi * kStar * radius * dWall;     // d/dd of π k R d²
    c.kSphere = kPi * kStar * radius * dSphere;     // d/dδ of (π/2) k R δ²
    return c;
}

bool hasShear(const Cube27Options& o, Formulation f)
{
    return normalModel(f).perNodeForces() && o.friction > 0 &&
           o.shearRatio > 0;
}

/// What sets a run's step count, for a plan refused as too long.
const char* const kCube27StepOptions =
    "check --speed (or --periods), --delta-max, --safety and --kn / --k-factors";

/// Refuse a run that @a takes (would take, needs at least) @a steps time steps (or not a
/// number) over the studies' limit.
void refuseCube27Steps(double steps, const char* takes, Formulation f, int nodes, double stiffness)
{
    if (steps <= double(kMaxStudySteps)) return;
    std::ostringstream s;
    s << "the run of " << formulationName(f) << " at N = " << nodes << ", k = " << stiffness
      << " " << takes << " " << steps << " time steps (the limit is " << double(kMaxStudySteps)
      << ")";
    throw Error("", s.str(), kCube27StepOptions);
}

} // namespace

Cube27Run planCube27Run(const Cube27Options& o, Formulation f, int nodes, double stiffness,
                        int orientation)
{
    Cube27Run run;
    run.formulation = f;
    run.nodes = nodes;
    run.stiffness = stiffness;
    run.orientation = orientation;

    const double mass = o.density * 4.0 / 3.0 * kPi * std::pow(o.radius, 3);
    const double inertia = 0.4 * mass * o.radius * o.radius;
    const ColumnStiffness c = columnStiffness(f, o.radius, o.deltaMax, stiffness, nodes);
    // Stiffest grain: the top (or bottom) sphere, a wall on one side and a sphere on the other;
    // the middle one has two sphere contacts.
    const double kGrain = std::max(c.kWall + c.kSphere, 2.0 * c.kSphere);
    // Translation plus rotation on the shear springs at distance R: the bound the stability
    // check takes (StableStep.h: the largest ω² of translation and rotation together is at
    // most the sum of each's).
    double omegaMax2 = kGrain / mass;
    if (hasShear(o, f)) omegaMax2 += o.shearRatio * kGrain * o.radius * o.radius / inertia;
    run.stabilityLimit = 2.0 / std::sqrt(omegaMax2);
    // A stiffness so large that ω² overflows (--kn 1e305) leaves no time step to plan with:
    // named here, rather than by the first run as a time step to fix.
    if (!(run.stabilityLimit > 0.0) || !std::isfinite(run.stabilityLimit))
        throw Error("", "the stiffness " + numberText(stiffness) +
                            " (--kn, or the paper's times a --k-factors factor) is too stiff: "
                            "the " + formulationName(f) + " run at N = " + std::to_string(nodes) +
                            " gets no time step (its stability limit is " +
                            numberText(run.stabilityLimit) + " s)",
                    "give a smaller --kn or --k-factors (the paper's stiffnesses are 1e9 N/mm "
                    "and 1e3 N/mm^3)");
    // Slowest vertical mode of a column (symmetric mode of wall–m–m–m–floor).
    const double trace = c.kWall + 3.0 * c.kSphere, det = 2.0 * c.kWall * c.kSphere;
    const double omega1 = std::sqrt((trace - std::sqrt(trace * trace - 4.0 * det)) / 2.0 / mass);
    const double loadingTime =
        o.speed > 0.0 ? o.deltaMax / o.speed : o.periods * 2.0 * kPi / omega1;

    // Step counts in double until they are known to fit: absurd but finite options (a
    // crawling wall, a tiny --safety) ask for more steps than any integer holds.
    const double fewestSteps = std::ceil(loadingTime / run.stabilityLimit);
    refuseCube27Steps(fewestSteps, "needs at least", f, nodes, stiffness);
    if (o.steps > 0) {
        run.steps = o.steps;
        run.timeStep = loadingTime / double(o.steps);
        if (run.timeStep > run.stabilityLimit) {
            std::ostringstream s;
            s << "--steps " << o.steps << " is too few for " << formulationName(f) << " at N = "
              << nodes << ", k = " << stiffness << ": the time step " << run.timeStep
              << " s would exceed the stack's stability limit " << run.stabilityLimit << " s";
            throw Error("", s.str(),
                        "give at least --steps " + std::to_string((long long)fewestSteps) +
                            " (5x that is safe), or leave --steps out");
        }
    } else {
        const double steps = std::ceil(loadingTime / (o.safety * run.stabilityLimit));
        refuseCube27Steps(steps, "would take", f, nodes, stiffness);  // NaN too, before max()
        run.steps = std::max(1LL, (long long)steps);
        run.timeStep = loadingTime / double(run.steps);
    }
    // Fewer steps than recorded points is no loading at all: the wall would jump.
    if (run.steps < o.points) {
        std::ostringstream s;
        s << "the run of " << formulationName(f) << " at N = " << nodes << ", k = " << stiffness
          << " would press the stack by delta_max in " << run.steps
          << " time step(s), fewer than the " << o.points << " points it records";
        throw Error("", s.str(),
                    "give a lower --speed or more --periods (or --steps), or fewer --points");
    }
    run.speed = o.deltaMax / (run.timeStep * double(run.steps));
    return run;
}

std::vector<Cube27Run> planCube27(const Cube27Options& o)
{
    checkCube27Options(o);
    const int kSeriesCount = stiffnessSeriesNodes(o);
    std::vector<Cube27Run> runs;
    for (int nodes : o.nodeCounts)
        for (Formulation f : o.formulations) {
            std::vector<double> ks;
            if (!o.stiffness.empty()) ks = o.stiffness;
            else if (nodes == kSeriesCount)
                for (double factor : o.stiffnessFactors) ks.push_back(factor * normalModel(f).paperStiffness());
            else ks.push_back(normalModel(f).paperStiffness());
            for (double k : ks)
                for (int m = 0; m < o.orientations; ++m)
                    runs.push_back(planCube27Run(o, f, nodes, k, m));
        }
    double steps = 0.0;
    for (const Cube27Run& run : runs) steps += double(run.steps);
    if (steps > double(kMaxStudySteps)) {
        std::ostringstream s;
        s << "the study would take " << steps << " time steps in its " << runs.size()
          << " runs (the limit is " << double(kMaxStudySteps) << ")";
        throw Error("", s.str(), std::string(kCube27StepOptions) + ", or run fewer --nodes");
    }
    return runs;
}

} // namespace lsdem
