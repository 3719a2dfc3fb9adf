#include "studies/TriaxialPathControl.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

void holdStress(World& w, const TriaxialWalls& walls, int axis, const TriaxialProtocol& p,
                double maxSpeed)
{
    if (walls.periodic) {
        w.periodic.targetStress[axis] = p.confiningStress;
        w.periodic.maxStrainRate[axis] = 2.0 * maxSpeed / w.periodic.size[axis];
        return;
    }
    if (walls.hasMembrane() && axis < 2) {  // the cell pressure does it, steered
        w.membranes[size_t(walls.membrane)].targetStress = p.confiningStress;
        steerMembranePressure(w, walls, kMembraneGain);
        return;
    }
    for (int side = 0; side < 2; ++side) {
        StressServo& s = wallOf(w, walls, 2 * axis + side).servo;
        s.targetStress = p.confiningStress;
        // In a membrane, the platens push on the sample's mean cross-section now (renewed
        // at each call: the stages call this every hundred steps).
        s.area = walls.hasMembrane() ? membraneSampleArea(w, walls) : 0.0;
        s.areaWalls = areaWallsOf(walls, axis);
        s.gain = p.servoGain;
        s.maxSpeed = maxSpeed;
    }
}

void setTargetStress(World& w, const TriaxialWalls& walls, int axis, double stress)
{
    if (walls.periodic) {
        w.periodic.targetStress[axis] = stress;
        return;
    }
    if (walls.hasMembrane() && axis < 2) {
        w.membranes[size_t(walls.membrane)].targetStress = stress;
        return;
    }
    for (int side = 0; side < 2; ++side) wallOf(w, walls, 2 * axis + side).servo.targetStress = stress;
}

double unloadStrainOf(const TriaxialProtocol& p)
{
    return p.unloadStrain > 0.0 ? p.unloadStrain : 0.5 * p.maxAxialStrain;
}

TriaxialPathControl::TriaxialPathControl(World& w, const TriaxialWalls& walls,
                                         const TriaxialProtocol& p,
                                         const TriaxialState& reference, double dt)
    : mWorld(w), mWalls(walls), mP(p), mReference(reference), mDt(dt),
      mEndSpeed(0.5 * p.strainRate * reference.size.z())
{
    for (int axis = 0; axis < 2; ++axis)
        holdStress(w, walls, axis, p, p.strainRate * reference.size[axis]);
    setTargetStress(w, walls, 2, 0.0);  // the axis is strained, not servoed
    if (p.path == TriaxialPath::Undrained)  // (a membrane's pressure then follows the volume)
        for (int axis = 0; axis < 2; ++axis) setTargetStress(w, walls, axis, 0.0);
    mDirection = p.path == TriaxialPath::Extension ? -1.0 : 1.0;
    setWalls(reference);
}

bool TriaxialPathControl::update(const TriaxialState& now, double strain)
{
    const double direction = mDirection;
    const bool going = turn(now, strain);
    turned = mDirection != direction;
    if (going) setWalls(now);
    return going;
}

bool TriaxialPathControl::turn(const TriaxialState& now, double strain)
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

void TriaxialPathControl::setWalls(const TriaxialState& now)
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
        if (mWalls.hasMembrane()) {
            holdVolumeByPressure(now);
            break;
        }
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

void TriaxialPathControl::holdVolumeByPressure(const TriaxialState& now)
{
    // (Measured on 182 grains: this gain holds the volume within 0.2 %; ten times it rings.)
    const double swelling = (now.volume - mReference.volume) / mReference.volume;
    Membrane& m = mWorld.membranes[size_t(mWalls.membrane)];
    m.pressure = std::max(m.pressure + kUndrainedVolumeGain * mP.confiningStress * swelling,
                          1e-3 * mP.confiningStress);
}

void TriaxialPathControl::moveSidesKeepingTheVolume(const TriaxialState& now)
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

} // namespace lsdem
