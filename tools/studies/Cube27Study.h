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
///   (cube27ColumnStiffness); the original law is treated as the adapted one with the
///   effective kn* = kn·N/(4πR²) of N uniformly spread nodes (SCIENCE.md §2–3);
/// - time step: dt = safety·2/ω_max, ω_max² the stiffest grain's (the top sphere, wall above
///   and sphere below) largest of K/m (normal) and (ks/kn)·K·R²/I (rotation on the shear
///   springs). The automatic step of lsdem-run knows one node only and is far too large here;
///   Simulation's stability check still guards every step;
/// - loading time: `periods` periods of the slowest vertical mode of a column at δ_max, so the
///   wall speed scales with sqrt(stiffness/mass): original and adapted runs are dynamically
///   similar and cost the same number of steps.
#pragma once

#include "studies/SphereSeriesOptions.h"

#include "lsdem/contact/ContactModel.h"
#include "lsdem/scene/Scene.h"

#include <string>
#include <vector>

namespace lsdem {

struct Cube27Options : SphereSeriesOptions
{
    Cube27Options()
    {
        nodeCounts = {500, 1000, 2000, 4000, 8000};
        kSeriesNodes = 4000;  // the paper's N for Fig. 4C, 4E
        voxel = 0.1;
        deltaMax = 0.3;       // top wall travel
        orientations = 1;
        outDir = "results/cube27";
    }
    double speed = 0.0;             ///< mm/s; 0: from `periods` (dynamically similar runs)
    long long steps = 0;            ///< loading steps; 0: from the time step below
    double periods = 100.0;         ///< loading time in periods of a column's slowest mode
    double safety = 0.2;            ///< dt as a fraction of the stiffest grain's stability limit
    int points = 30;                ///< δ values recorded (plus δ = 0)
    double density = 7.85e-9;       ///< tonne/mm³ (steel)
    double friction = 0.3;
    double shearRatio = 0.5;        ///< ks/kn (ks*/kn*)
    double restitution = 0.5;       ///< contact dashpots
    double globalDamping = 0.3;
};

/// The paper-like study (--full): nodes 500 … 16000, three orientations, voxel 0.05 mm.
Cube27Options cube27FullOptions();

/// Check @a o and throw Error naming the bad option and the fix.
void checkCube27Options(const Cube27Options& o);

/// Closed form (parabolic caps, small δ/R) of the adapted law: each of the 9 columns is
/// wall–sphere (P = π·k·R·d_w², exact for a plane), sphere–sphere twice (P = (π/2)·k·R·d_s²)
/// and sphere–floor in series, so d_s = √2·d_w, δ = (2 + 2√2)·d_w and
/// P = 9·π·k·R·δ² / (2 + 2√2)².
double cube27ClosedForm(double radius, double delta, double knStar);

/// The same continuum limit without the parabolic approximation of the sphere–sphere caps:
/// the sphere–sphere force is exactSphereContactForce (1-D quadrature), and d_w is found so
/// that 2·d_w + 2·d_s = δ with equal forces in every contact of a column.
double cube27ExactForce(double radius, double delta, double knStar);

/// The continuum kn* that the original law with stiffness @a kn behaves like with @a nodes
/// nodes spread uniformly over @a area: kn·N / area.
double originalEffectiveStiffness(double kn, double nodes, double area);

/// One simulation of the study: a formulation, node count, stiffness and orientation set.
struct Cube27Run
{
    Formulation formulation = Formulation::Adapted;
    int nodes = 0;
    double stiffness = 0.0;
    int orientation = 0;
    // The loading plan.
    double timeStep = 0.0;    ///< s
    long long steps = 0;      ///< loading steps
    double speed = 0.0;       ///< mm/s
    double stabilityLimit = 0.0;  ///< the planned stiffest grain's limit 2/ω_max, s
    // What happened.
    double seconds = 0.0;
    double stabilityLimitSeen = 0.0;  ///< Simulation's smallest limit met, s
    long long contactNodes = 0;       ///< penetrating nodes at the end
};

/// Plan the loading of one run (time step, steps, speed) from closed forms; see the file note.
Cube27Run planCube27Run(const Cube27Options& o, Formulation f, int nodes, double stiffness,
                        int orientation);

/// All runs of the study, in the order they are made (per node count: formulations ×
/// stiffnesses × orientations).
std::vector<Cube27Run> planCube27(const Cube27Options& o);

/// The scene of one run: 27 spheres of @a asset (an analytic sphere baked at load, or
/// @a assetFile if given), randomly oriented per grain from the run's orientation seed, six
/// plane walls, the contact model, no gravity, global damping, the planned time step and
/// end displacement.
Scene makeCube27Scene(const Cube27Options& o, const Cube27Run& run,
                      const std::string& assetFile = "");

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

/// Run the study (no files written). Prints the plan and each run's wall time unless quiet.
Cube27Result runCube27(const Cube27Options& o);

/// Write @a result as CSV to @a path (atomically).
void writeCube27Csv(const Cube27Result& result, const Cube27Options& o, const std::string& path);

} // namespace lsdem
