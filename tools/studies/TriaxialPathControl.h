/// @file TriaxialPathControl.h
/// @brief How the triaxial cell's walls (or its periodic cell) follow a loading path
///        (TriaxialPath.h) step by step, and the servo settings the stages share.
#pragma once

#include "studies/TriaxialTest.h"

namespace lsdem {

/// A membrane's pressure moves by this fraction of what the grains' lateral stress lacks of its
/// target, at each of the stages' checks (every hundred steps consolidating, every ten
/// shearing): slow beside the membrane's own response, so it does not chase its vibrations.
inline constexpr double kMembraneGain = 0.5;

/// Undrained in a membrane: after each step the pressure grows by this·σ₃ times the relative
/// change of the enclosed volume (an integral servo on the volume), so the sample keeps its
/// volume while the grains' lateral stress goes where it must.
inline constexpr double kUndrainedVolumeGain = 0.5;

/// Make the walls of @a axis keep σ₃ with limit speed @a maxSpeed (in a periodic cell: its
/// axis, at most at the strain rate of two walls at that speed).
void holdStress(World& w, const TriaxialWalls& walls, int axis, const TriaxialProtocol& p,
                double maxSpeed);

/// The stress the servo of @a axis's walls (or the periodic cell's @a axis) aims at.
void setTargetStress(World& w, const TriaxialWalls& walls, int axis, double stress);

/// UnloadReload: the axial strain where the unloading starts.
double unloadStrainOf(const TriaxialProtocol& p);

/// The walls along the path, step by step: the end walls at ε̇·H₀/2 each, closing (or opening),
/// the side walls by servo (fast enough for a dilation rate of 2ε̇) or, undrained, moved so the
/// cell keeps its volume.
class TriaxialPathControl
{
public:
    TriaxialPathControl(World& w, const TriaxialWalls& walls, const TriaxialProtocol& p,
                        const TriaxialState& reference, double dt);

    /// After a step, with the cell now in @a now at axial strain @a strain: the walls for the
    /// next step. False once a path that ends by its strain has ended.
    bool update(const TriaxialState& now, double strain);

    double unloadModulus = 0.0;
    bool turned = false;  ///< the last update reversed the ends

private:
    /// The path's phase after a step; false once it has ended.
    bool turn(const TriaxialState& now, double strain);
    void setWalls(const TriaxialState& now);
    /// Undrained between walls: the height after the next step, and the sides' sizes that keep
    /// L_x·L_y·H (each in proportion to its consolidated size): each side wall moves half the
    /// difference.
    void moveSidesKeepingTheVolume(const TriaxialState& now);
    /// Undrained in a membrane: the target of the grains' lateral stress from the volume's
    /// change (kUndrainedFluidStiffness).
    void holdVolumeByPressure(const TriaxialState& now);

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

} // namespace lsdem
