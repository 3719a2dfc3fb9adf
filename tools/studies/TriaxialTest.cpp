#include "studies/TriaxialTest.h"

#include "studies/StudyLimits.h"
#include "studies/TriaxialPathControl.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem {

namespace {

double& grainFriction(World& w)
{
    return w.models[0].friction;  // material 0 with itself
}

TriaxialRow measureRow(const Simulation& sim, const TriaxialWalls& walls, int stage,
                       const TriaxialState* reference, const TriaxialProtocol& p)
{
    TriaxialRow r;
    r.stage = stage;
    r.step = sim.world().step;
    r.time = sim.world().time;
    r.state = measureTriaxialCell(sim.world(), walls, sim.contactRecords());
    if (reference) {
        r.axialStrain = axialStrain(*reference, r.state);
        r.volumetricStrain = volumetricStrain(*reference, r.state);
        if (r.state.p > 0.0)
            r.inertialNumber = p.strainRate * p.grainDiameter * std::sqrt(p.density / r.state.p);
    }
    r.frictionAngle = p.path == TriaxialPath::TrueTriaxial ? principalFrictionAngle(r.state)
                                                            : mobilisedFrictionAngle(r.state);
    r.kinetic = sim.energies().kinetic;
    return r;
}

bool withinTolerance(const TriaxialState& s, const TriaxialProtocol& p)
{
    for (int axis = 0; axis < 3; ++axis)
        if (!(std::abs(s.stress[axis] / p.confiningStress - 1.0) < p.stressTolerance)) return false;
    return true;
}

/// The axial strain the path travels at most.
double axialTravel(const TriaxialProtocol& p)
{
    switch (p.path) {
    case TriaxialPath::UnloadReload: return p.maxAxialStrain + 2.0 * unloadStrainOf(p);
    case TriaxialPath::Cyclic: return 4.0 * p.maxAxialStrain * double(p.cycles);
    default: return p.maxAxialStrain;
    }
}

/// Whether the path runs a fixed count of steps (to maxAxialStrain, one way) or until its
/// strain and stress say it is done.
bool monotonic(TriaxialPath path)
{
    return path != TriaxialPath::UnloadReload && path != TriaxialPath::Cyclic;
}

} // namespace

long long triaxialShearSteps(const TriaxialProtocol& p, double dt)
{
    // In double until it is known to fit: a tiny rate or step needs more than any integer holds.
    const double steps = std::ceil(axialTravel(p) / (p.strainRate * dt));
    if (!(steps >= 1.0 && steps <= double(kMaxStudySteps))) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "the shearing would take %.3g time steps of %.3g s at the strain rate "
                      "%.3g /s (the limit is %.3g)",
                      steps, dt, p.strainRate, double(kMaxStudySteps));
        throw Error("", text,
                    "check --inertial-number and --axial-strain (the rate and the strain), and "
                    "--kn-star, --kn-original and --density (the time step)");
    }
    return static_cast<long long>(steps);
}

TriaxialTestResult runTriaxialTest(Simulation& sim, const TriaxialWalls& walls,
                                   const TriaxialProtocol& p,
                                   const std::function<void(const TriaxialRow&)>& progress)
{
    triaxialShearSteps(p, sim.timeStep());  // refused before consolidating
    TriaxialTestResult result = consolidateTriaxial(sim, walls, p, progress);
    shearTriaxial(sim, walls, p, result, progress);
    return result;
}

TriaxialTestResult consolidateTriaxial(Simulation& sim, const TriaxialWalls& walls,
                                       const TriaxialProtocol& p,
                                       const std::function<void(const TriaxialRow&)>& progress)
{
    TriaxialTestResult result;
    auto record = [&](TriaxialRow row) {
        if (progress) progress(row);
        result.rows.push_back(std::move(row));
    };
    // Isotropic consolidation: six servo walls close in on the cloud until every stress is
    // within the tolerance of σ₃ for settledSteps.
    World& w = sim.world();
    const TriaxialState start = measureTriaxialCell(w, walls, {});
    auto limitSpeeds = [&](double rate) {
        for (int axis = 0; axis < 3; ++axis)
            holdStress(w, walls, axis, p, 0.5 * rate * start.size[axis]);
    };
    // (A sample in a membrane was cut from one consolidated between walls: it is dense already,
    // and its platens must not rush at it while the membrane closes in.)
    const double approachRate = walls.hasMembrane() ? p.consolidationRate : p.approachRate;
    limitSpeeds(approachRate);
    grainFriction(w) = p.consolidationFriction;
    sim.invalidateContacts();
    const long long firstStep = w.step;
    long long settledSince = -1;
    constexpr long long kCheckEvery = 100, kRecordEvery = 1000;
    // The pace of the last thousand steps (at most) of the consolidation, for the estimate.
    Stopwatch paceClock;
    long long paceFrom = w.step;
    double paceSeconds = 0.0;
    long long paceSteps = 0;
    while (w.step - firstStep < p.maxConsolidationSteps) {
        for (long long k = 0; k < kCheckEvery; ++k) sim.step();
        const TriaxialState now = measureTriaxialCell(w, walls, {});
        limitSpeeds(now.p < 0.5 * p.confiningStress ? approachRate : p.consolidationRate);
        if (withinTolerance(now, p)) {
            if (settledSince < 0) settledSince = w.step;
            if (w.step - settledSince >= p.settledSteps) {
                result.consolidatedWithinTolerance = true;
                break;
            }
        } else {
            settledSince = -1;
        }
        if ((w.step - firstStep) % kRecordEvery == 0) {
            paceSeconds = paceClock.seconds();
            paceSteps = w.step - paceFrom;
            paceClock.restart();
            paceFrom = w.step;
            record(measureRow(sim, walls, 0, nullptr, p));
        }
    }
    if (w.step - paceFrom >= kRecordEvery / 2 || paceSteps == 0) {  // a later, long enough stretch
        paceSeconds = paceClock.seconds();
        paceSteps = w.step - paceFrom;
    }
    result.consolidationSteps = w.step - firstStep;
    result.paceSteps = paceSteps;
    result.paceSeconds = paceSeconds;
    result.consolidated = measureTriaxialCell(w, walls, sim.contactRecords());
    for (const Grain& g : w.grains) result.consolidatedPoses.push_back(g.body.pose);
    for (int k = 0; k < 6 && !walls.periodic; ++k) {
        if (walls.index[size_t(k)] < 0) continue;  // a membrane's sides
        const Boundary& b = wallOf(w, walls, k);
        result.consolidatedWallPoints[size_t(k)] = b.plane.point + b.displacement;
    }
    return result;
}


void shearTriaxial(Simulation& sim, const TriaxialWalls& walls, const TriaxialProtocol& p,
                   TriaxialTestResult& result,
                   const std::function<void(const TriaxialRow&)>& progress)
{
    const long long shearSteps = triaxialShearSteps(p, sim.timeStep());
    auto record = [&](TriaxialRow row) {
        if (progress) progress(row);
        result.rows.push_back(std::move(row));
    };
    World& w = sim.world();
    const TriaxialState& reference = result.consolidated;
    TriaxialRow first = measureRow(sim, walls, 1, &reference, p);
    if (result.paceSteps > 0)
        first.shearSecondsEstimate =
            double(shearSteps) * result.paceSeconds / double(result.paceSteps);
    result.shearSecondsEstimate = first.shearSecondsEstimate;
    const Stopwatch shearClock;
    record(first);
    grainFriction(w) = p.friction;
    TriaxialPathControl control(w, walls, p, reference, sim.timeStep());
    const long long recordEvery = std::max(1LL, shearSteps / p.records);
    const long long shearStart = w.step;
    // A monotonic path runs its steps; the others until their strain says they are done (at
    // most the steps of their longest travel).
    const bool counted = monotonic(p.path);
    // (Each turn overshoots its strain by up to a step: a few steps of slack for the turns.)
    const long long limit = counted ? shearSteps : shearSteps + 4LL * (p.cycles + 2);
    bool going = true;
    while (going && w.step - shearStart < limit) {
        sim.step();
        const long long done = w.step - shearStart;
        if (walls.hasMembrane() && done % 10 == 0) steerMembranePressure(w, walls, kMembraneGain);
        if (!counted) {
            const TriaxialState now = measureTriaxialCell(w, walls, {});
            going = control.update(now, axialStrain(reference, now));
        } else if (p.path != TriaxialPath::Compression && p.path != TriaxialPath::Extension) {
            control.update(measureTriaxialCell(w, walls, {}), 0.0);
        }
        if (done % recordEvery == 0 || done == shearSteps || !going || control.turned)
            record(measureRow(sim, walls, 1, &reference, p));
    }
    result.shearSteps = w.step - shearStart;
    result.shearSeconds = shearClock.seconds();
    result.unloadReloadModulus = control.unloadModulus;
    summariseTriaxialShearing(result, p.maxAxialStrain);
}

void summariseTriaxialShearing(TriaxialTestResult& r, double maxAxialStrain)
{
    double phiSum = 0.0, eSum = 0.0;
    int critical = 0;
    r.peakFrictionAngle = r.peakAxialStrain = r.maxInertialNumber = 0.0;
    for (const TriaxialRow& row : r.rows) {
        if (row.stage != 1) continue;
        if (row.frictionAngle > r.peakFrictionAngle) {
            r.peakFrictionAngle = row.frictionAngle;
            r.peakAxialStrain = row.axialStrain;
        }
        r.maxInertialNumber = std::max(r.maxInertialNumber, row.inertialNumber);
        if (std::abs(row.axialStrain) >= 0.75 * maxAxialStrain) {
            phiSum += row.frictionAngle;
            eSum += row.state.voidRatio;
            ++critical;
        }
    }
    // E₅₀ from the rising branch: the first row at half the peak deviator, interpolated.
    double peakQ = 0.0;
    for (const TriaxialRow& row : r.rows)
        if (row.stage == 1) peakQ = std::max(peakQ, row.state.q);
    r.secantModulus50 = 0.0;
    const TriaxialRow* before = nullptr;
    for (const TriaxialRow& row : r.rows) {
        if (row.stage != 1) continue;
        if (before && row.state.q >= 0.5 * peakQ && peakQ > 0.0) {
            const double t = (0.5 * peakQ - before->state.q) / (row.state.q - before->state.q);
            const double strain = before->axialStrain + t * (row.axialStrain - before->axialStrain);
            if (strain > 0.0) r.secantModulus50 = 0.5 * peakQ / strain;
            break;
        }
        before = &row;
    }
    r.criticalFrictionAngle = critical > 0 ? phiSum / critical : 0.0;
    r.criticalVoidRatio = critical > 0 ? eSum / critical : 0.0;
}

} // namespace lsdem
