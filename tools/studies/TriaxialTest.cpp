#include "studies/TriaxialTest.h"

#include "studies/StudyLimits.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem {

namespace {

Boundary& wallOf(World& w, const TriaxialWalls& walls, int which)
{
    return w.boundaries[size_t(walls.index[size_t(which)])];
}

/// Make the walls of @a axis keep σ₃ with limit speed @a maxSpeed (in a periodic cell: its
/// axis, at most at the strain rate of two walls at that speed).
void holdStress(World& w, const TriaxialWalls& walls, int axis, const TriaxialProtocol& p,
                double maxSpeed)
{
    if (walls.periodic) {
        w.periodic.targetStress[axis] = p.confiningStress;
        w.periodic.maxStrainRate[axis] = 2.0 * maxSpeed / w.periodic.size[axis];
        return;
    }
    for (int side = 0; side < 2; ++side) {
        StressServo& s = wallOf(w, walls, 2 * axis + side).servo;
        s.targetStress = p.confiningStress;
        s.area = 0.0;
        s.areaWalls = areaWallsOf(walls, axis);
        s.gain = p.servoGain;
        s.maxSpeed = maxSpeed;
    }
}

/// The stress the servo of @a axis's walls (or the periodic cell's @a axis) aims at.
void setTargetStress(World& w, const TriaxialWalls& walls, int axis, double stress)
{
    if (walls.periodic) {
        w.periodic.targetStress[axis] = stress;
        return;
    }
    for (int side = 0; side < 2; ++side) wallOf(w, walls, 2 * axis + side).servo.targetStress = stress;
}

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

/// UnloadReload: where the unloading starts.
double unloadStrainOf(const TriaxialProtocol& p)
{
    return p.unloadStrain > 0.0 ? p.unloadStrain : 0.5 * p.maxAxialStrain;
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

/// The walls along the path, step by step: the end walls at ε̇·H₀/2 each, closing (or opening),
/// the side walls by servo (fast enough for a dilation rate of 2ε̇) or, undrained, moved so the
/// cell keeps its volume.
class PathControl
{
public:
    PathControl(World& w, const TriaxialWalls& walls, const TriaxialProtocol& p,
                const TriaxialState& reference, double dt)
        : mWorld(w), mWalls(walls), mP(p), mReference(reference), mDt(dt),
          mEndSpeed(0.5 * p.strainRate * reference.size.z())
    {
        for (int axis = 0; axis < 2; ++axis)
            holdStress(w, walls, axis, p, p.strainRate * reference.size[axis]);
        setTargetStress(w, walls, 2, 0.0);  // the axis is strained, not servoed
        if (p.path == TriaxialPath::Undrained)
            for (int axis = 0; axis < 2; ++axis) setTargetStress(w, walls, axis, 0.0);
        mDirection = p.path == TriaxialPath::Extension ? -1.0 : 1.0;
        setWalls(reference);
    }

    /// After a step, with the cell now in @a now at axial strain @a strain: the walls for the
    /// next step. False once a path that ends by its strain has ended.
    bool update(const TriaxialState& now, double strain)
    {
        const double direction = mDirection;
        const bool going = turn(now, strain);
        turned = mDirection != direction;
        if (going) setWalls(now);
        return going;
    }

    double unloadModulus = 0.0;
    bool turned = false;  ///< the last update reversed the ends

private:
    /// The path's phase after a step; false once it has ended.
    bool turn(const TriaxialState& now, double strain)
    {
        const double amplitude = mP.maxAxialStrain;
        switch (mP.path) {
        case TriaxialPath::UnloadReload:
            if (mPhase == 0 && strain >= unloadStrainOf(mP)) {
                mPhase = 1, mDirection = -1.0, mReversalQ = now.q, mReversalStrain = strain;
            } else if (mPhase == 1 && (now.q <= 0.1 * mReversalQ || strain <= 0.0)) {
                if (mReversalStrain > strain)
                    unloadModulus = (mReversalQ - now.q) / (mReversalStrain - strain);
                mPhase = 2, mDirection = 1.0;
            } else if (mPhase == 2 && strain >= amplitude) {
                return false;
            }
            break;
        case TriaxialPath::Cyclic:
            if (mDirection > 0.0 && mTurnsAtBottom == mP.cycles && strain >= 0.0) return false;
            if (mDirection > 0.0 && strain >= amplitude) mDirection = -1.0;
            if (mDirection < 0.0 && strain <= -amplitude) mDirection = 1.0, ++mTurnsAtBottom;
            break;
        default: break;
        }
        return true;
    }

    void setWalls(const TriaxialState& now)
    {
        PeriodicCell& cell = mWorld.periodic;
        if (mWalls.periodic) {  // the height changes at 2·ε̇·H₀/2, as between two end walls
            cell.strainRate.z() = -mDirection * 2.0 * mEndSpeed / now.size.z();
        } else {
            for (int side = 0; side < 2; ++side) {
                Boundary& b = wallOf(mWorld, mWalls, 4 + side);
                b.velocity = mDirection * mEndSpeed * b.plane.normal;
            }
        }
        const double sigma3 = mP.confiningStress, axial = now.stress.z();
        switch (mP.path) {
        case TriaxialPath::ConstantP:
            // p = (σ_a + 2σ_r)/3 = σ₃; a servo needs a positive target (0 turns it off).
            for (int axis = 0; axis < 2; ++axis)
                setTargetStress(mWorld, mWalls, axis,
                                std::max(0.5 * (3.0 * sigma3 - axial), 1e-3 * sigma3));
            break;
        case TriaxialPath::TrueTriaxial:
            setTargetStress(mWorld, mWalls, 1, sigma3 + mP.b * (axial - sigma3));
            break;
        case TriaxialPath::Undrained:
            if (mWalls.periodic) {
                // The cell's next step scales z by 1 + ε̇_z·dt: x and y by its inverse root.
                const double rate =
                    (1.0 / std::sqrt(1.0 + cell.strainRate.z() * mDt) - 1.0) / mDt;
                cell.strainRate.x() = cell.strainRate.y() = rate;
                break;
            }
            moveSidesKeepingTheVolume(now);
            break;
        default: break;
        }
    }

    /// Undrained between walls: the height after the next step, and the sides' sizes that keep
    /// L_x·L_y·H (each in proportion to its consolidated size): each side wall moves half the
    /// difference.
    void moveSidesKeepingTheVolume(const TriaxialState& now)
    {
        const double height = now.size.z() - 2.0 * mDirection * mEndSpeed * mDt;
        const double scale = std::sqrt(mReference.size.z() / height);
        for (int axis = 0; axis < 2; ++axis) {
            const double inward = (now.size[axis] - scale * mReference.size[axis]) / (2.0 * mDt);
            for (int side = 0; side < 2; ++side) {
                Boundary& b = wallOf(mWorld, mWalls, 2 * axis + side);
                b.velocity = inward * b.plane.normal;
            }
        }
    }

    World& mWorld;
    const TriaxialWalls& mWalls;
    const TriaxialProtocol& mP;
    const TriaxialState& mReference;
    double mDt, mEndSpeed;
    double mDirection = 1.0;
    int mPhase = 0;           ///< UnloadReload: 0 loading, 1 unloading, 2 reloading
    int mTurnsAtBottom = 0;   ///< Cyclic: turns at −A so far
    double mReversalQ = 0.0, mReversalStrain = 0.0;
};

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
    limitSpeeds(p.approachRate);
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
        limitSpeeds(now.p < 0.5 * p.confiningStress ? p.approachRate : p.consolidationRate);
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
    PathControl control(w, walls, p, reference, sim.timeStep());
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
