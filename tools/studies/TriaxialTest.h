/// @file TriaxialTest.h
/// @brief The triaxial test on a cell of six plane walls (TriaxialCell.h): isotropic
///        consolidation to σ₃ by six servo walls, then a loading path (TriaxialPath.h) at a
///        constant axial strain rate, by default drained compression (the top and bottom walls
///        move towards each other while the four side walls keep σ₃), to a given axial strain.
///        Records q, p, strains, void ratio, coordination and the inertial number along the way.
#pragma once

#include "lsdem/scene/Scene.h"

#include "studies/TriaxialCell.h"
#include "studies/TriaxialPath.h"

#include <functional>
#include <vector>

namespace lsdem {

class Simulation;

struct TriaxialProtocol
{
    double confiningStress = 0.1;  ///< σ₃ > 0, force/length² (compression positive)
    double strainRate = 1.0;       ///< axial ε̇ while shearing, 1/time
    /// Consolidation: each wall's servo limit speed is this strain rate times half the cell's
    /// size along its axis at the start, ...
    double consolidationRate = 10.0;
    /// ... and this one while the mean stress is below σ₃/2 (the walls closing in on a loose
    /// cloud: how fast they come does not change where a frictionless consolidation ends). An
    /// absolute rate (1/time), not a multiple of the strain rate: the studies keep 100 s⁻¹.
    double approachRate = 100.0;
    double maxAxialStrain = 0.2;
    double stressTolerance = 0.02; ///< consolidated: every |σ_i/σ₃ − 1| below it ...
    long long settledSteps = 2000; ///< ... at every check over this many steps
    long long maxConsolidationSteps = 400000;  ///< give up (result says so) after this many
    double friction = 0.5;         ///< grain–grain μ while shearing (material 0 with itself)
    double consolidationFriction = 0.0;  ///< ... and while consolidating
    double servoGain = 0.5;        ///< α of every servo wall (StressServo.h)
    double grainDiameter = 1.0;    ///< mean equivalent diameter, for the inertial number
    double density = 1.0;          ///< grain density, for the inertial number
    int records = 200;             ///< rows over the shearing
    TriaxialPath path = TriaxialPath::Compression;
    double b = 0.5;                ///< TrueTriaxial: (σ₂ − σ₃)/(σ₁ − σ₃), in [0, 1]
    /// UnloadReload: the axial strain where the unloading starts (0: half maxAxialStrain)
    double unloadStrain = 0.0;
    int cycles = 2;                ///< Cyclic: cycles of amplitude maxAxialStrain
};

struct TriaxialRow
{
    int stage = 0;                 ///< 0 consolidation, 1 shearing
    long long step = 0;
    double time = 0.0;
    TriaxialState state;
    double axialStrain = 0.0, volumetricStrain = 0.0;  ///< from the consolidated state
    double frictionAngle = 0.0;    ///< mobilised, degrees
    double inertialNumber = 0.0;   ///< ε̇·d·sqrt(ρ/p)
    double kinetic = 0.0;          ///< kinetic energy
    /// On the first shearing row: the shearing's steps times the pace of the consolidation's
    /// last thousand steps (the sample dense by then), s; −1 on every other row.
    double shearSecondsEstimate = -1.0;
};

struct TriaxialTestResult
{
    std::vector<TriaxialRow> rows;
    TriaxialState consolidated;    ///< where the shearing starts (its reference)
    std::vector<RigidPose> consolidatedPoses;  ///< every grain's pose then
    std::array<Vec3, 6> consolidatedWallPoints;  ///< each wall's point then (walls' order)
    /// In a membrane (--boundary membrane): the sample's index of each grain of
    /// consolidatedPoses (empty: every grain of the sample, in order), the tube the membrane
    /// was made as (its rubber's unstretched shape; pressure and drag as consolidation left
    /// them) and its vertices then.
    std::vector<long long> consolidatedGrains;
    MembraneSpec consolidatedTube;
    std::vector<Vec3> consolidatedMembrane;
    bool consolidatedWithinTolerance = false;
    long long consolidationSteps = 0, shearSteps = 0;
    /// The shearing's wall time, s, and what was estimated for it when it began (−1: none).
    double shearSeconds = 0.0, shearSecondsEstimate = -1.0;
    double peakFrictionAngle = 0.0, peakAxialStrain = 0.0;
    /// Critical state: means over the last quarter of the axial strain.
    double criticalFrictionAngle = 0.0, criticalVoidRatio = 0.0;
    double maxInertialNumber = 0.0;  ///< over the shearing rows
    /// E₅₀: the secant modulus q/ε_a where q first reaches half its peak (between rows:
    /// linear), the stiffness of the sample; force/length².
    double secantModulus50 = 0.0;
    /// UnloadReload: E_ur, the secant Δq/Δε_a of the unloading (from the reversal to where q
    /// fell to a tenth of its value there); 0 on the other paths.
    double unloadReloadModulus = 0.0;
    /// The consolidation's last stretch, for the shearing's time estimate: steps and seconds.
    long long paceSteps = 0;
    double paceSeconds = 0.0;
};

/// The first stage alone: consolidate @a sim's grains to σ₃ (the rows of stage 0, the
/// consolidated state and poses). shearTriaxial continues from it, on this simulation or on a
/// copy of it (each path from the same consolidated sample).
TriaxialTestResult consolidateTriaxial(Simulation& sim, const TriaxialWalls& walls,
                                       const TriaxialProtocol& protocol,
                                       const std::function<void(const TriaxialRow&)>& progress = {});

/// The second stage: protocol.path from @a result's consolidated state, which @a sim is in,
/// its rows (stage 1) and summary added to @a result.
/// @throw Error as triaxialShearSteps, before any step.
void shearTriaxial(Simulation& sim, const TriaxialWalls& walls, const TriaxialProtocol& protocol,
                   TriaxialTestResult& result,
                   const std::function<void(const TriaxialRow&)>& progress = {});

/// Both stages. Run the test on @a sim, whose world holds grains of material 0 inside @a walls
/// (fixed planes, perpendicular pairs). @a progress, if set, is told each recorded row.
/// @throw Error from the simulation (e.g. a time step too large for the contacts), or as
///        triaxialShearSteps before the consolidation.
TriaxialTestResult runTriaxialTest(Simulation& sim, const TriaxialWalls& walls,
                                   const TriaxialProtocol& protocol,
                                   const std::function<void(const TriaxialRow&)>& progress = {});

/// The shearing's steps at time step @a dt: the axial strain the path travels at most (to
/// maxAxialStrain; and back and forth for unload–reload and cycles) at the strain rate.
/// @throw Error naming the study's options that set them if they are not from 1 to
///        kMaxStudySteps (StudyLimits.h).
long long triaxialShearSteps(const TriaxialProtocol& protocol, double dt);

/// Peak and critical-state figures of @a result's shearing rows (runTriaxialTest calls it).
void summariseTriaxialShearing(TriaxialTestResult& result, double maxAxialStrain);

} // namespace lsdem
