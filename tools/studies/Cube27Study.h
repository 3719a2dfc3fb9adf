/// @file Cube27Study.h
/// @brief The 3×3×3 ordered-sphere benchmark (Feldfogel et al. 2024, Fig. 4): 27 equal spheres
///        in a simple-cubic stack that exactly fills a box [0, 6R]³ (spheres just touching each
///        other and the walls), fixed floor and four side walls, compressed by a top wall moving
///        down at constant speed. The reaction P on the top wall against its displacement δ,
///        per formulation, node count and stiffness, mean of random orientations of the grains.
///        Real dynamics: the scene is built in code (Scene → buildWorld → Simulation) and
///        stepped quasi-statically (no gravity, global and contact damping).
///
/// Loading plan (all from closed forms at δ_max, so the cost is known before any run starts):
/// - contact stiffnesses: the continuum tangent stiffness of the stack at δ_max
///   (Cube27Plan.h); the original law is treated as the adapted one with the
///   effective kn* = kn·N/(4πR²) of N uniformly spread nodes (SCIENCE.md §2–3);
/// - time step: dt = safety·2/ω_max, ω_max² the stiffest grain's (the top sphere, wall above
///   and sphere below) largest of K/m (normal) and (ks/kn)·K·R²/I (rotation on the shear
///   springs). The automatic step of lsdem-run knows one node only and is far too large here;
///   Simulation's stability check still guards every step;
/// - loading time: `periods` periods of the slowest vertical mode of a column at δ_max, so the
///   wall speed scales with sqrt(stiffness/mass): original and adapted runs are dynamically
///   similar and cost the same number of steps.
#pragma once

#include "studies/Cube27ClosedForm.h"
#include "studies/Cube27Options.h"
#include "studies/Cube27Plan.h"
#include "studies/Cube27Scene.h"
#include "studies/RunDistributor.h"

#include <string>
#include <vector>

namespace lsdem {

/// One row of results: one formulation, node count, stiffness and δ, over orientations.
struct Cube27Row
{
    Formulation formulation = Formulation::Adapted;
    int nodesRequested = 0;
    double nodesActual = 0;
    double stiffness = 0;
    double delta = 0;                 ///< top wall displacement, mm
    double forceMean = 0, forceStd = 0, forceMin = 0, forceMax = 0;  ///< P on the top wall, N
    double floorForce = 0;            ///< mean reaction on the floor, N (≈ P if quasi-static)
    double sideForce = 0;             ///< mean total |normal reaction| on the four side walls, N
    double forceClosed = 0;           ///< cube27ClosedForm (original: with the effective kn*)
    double forceExact = 0;            ///< cube27ExactForce, likewise
};

struct Cube27Result
{
    std::vector<Cube27Row> rows;
    std::vector<Cube27Run> runs;
    double bakeSeconds = 0, simulateSeconds = 0;
};

/// Run the study (no files written), its runs spread by @a ranks. Prints the plan and each
/// run's wall time unless quiet. On rank 0 the result, the same on any number of ranks; the
/// other ranks do the runs rank 0 hands them and get an empty result.
Cube27Result runCube27(const Cube27Options& o, RunDistributor& ranks = serialRunDistributor());

/// Write @a result as CSV to @a path (atomically).
void writeCube27Csv(const Cube27Result& result, const Cube27Options& o, const std::string& path);

} // namespace lsdem
