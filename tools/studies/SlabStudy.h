/// @file SlabStudy.h
/// @brief The interlocked slab of Feldfogel et al. (2024), Fig. 5 and 6: an n×n panel of
///        interlocked blocks (SlabPanel.h) in a rigid frame, its central block pushed down by a
///        spherical indenter at constant speed; the indenter force P against its displacement δ
///        for each formulation and discretization, the two-way convergence study (SDP refined
///        at fixed VDP, then VDP at the converged SDP), and the state of the panel at chosen δ
///        (failure snapshots). Units: mm, N, s, tonne (so stresses in MPa = N/mm²).
///
/// Physical model (defaults, see SlabMaterial): blocks of soda-lime glass, E = 70 GPa,
/// ν = 0.22, ρ = 2.5e-9 t/mm³, μ = 0.4. The adapted normal stiffness is the elastic-foundation
/// modulus of a block loaded over a face: a traction p compresses a block of length L by
/// p·L/E, so kn* = E/L (traction per penetration; 8.75e3 N/mm³ for L = 8 mm), and
/// ks* = kn*/(2(1 + ν)) (the same with G for E). The original formulation gets a per-node
/// stiffness that matches the adapted one at a reference spacing s_ref:
/// kn = kn*·(√3/2)·s_ref² (a node's area on an equilateral mesh of edge s_ref), so the two
/// agree there and part as the surface is refined. The frame and the indenter are rigid and
/// touch the blocks with the same law. Damping: contact restitution 0.5 and YADE's global
/// damping 0.3 (quasi-static loading), gravity on.
#pragma once

#include "studies/SlabPanel.h"

#include "lsdem/contact/ContactModel.h"
#include "lsdem/scene/Scene.h"
#include "lsdem/ls/GrainAsset.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lsdem {

struct SlabMaterial
{
    double youngModulus = 7.0e4;   ///< E, N/mm² (70 GPa)
    double poisson = 0.22;         ///< ν
    double density = 2.5e-9;       ///< ρ, t/mm³
    double friction = 0.4;         ///< μ, block–block, block–frame and block–indenter
    double restitution = 0.5;      ///< contact damping (1: none)
    double globalDamping = 0.3;    ///< λ, non-viscous
    double gravity = 9810.0;       ///< mm/s², downward (0: none)
};

struct SlabStudyOptions
{
    SlabPanelOptions panel;
    SlabMaterial material;
    double knStar = 0.0;           ///< adapted kn*, N/mm³ (0: E/L)
    double ksStar = 0.0;           ///< adapted ks*, N/mm³ (0: kn*/(2(1+ν)))
    double knOriginal = 0.0;       ///< original kn, N/mm (0: kn*·(√3/2)·s_ref²)
    double referenceSdp = 0.0;     ///< s_ref for the default kn, mm (0: the coarsest SDP run)
    NodeTesting testing = NodeTesting::Symmetric;

    double indenterRadius = 2.5;   ///< mm
    /// Indenter speed, mm/s. Quasi-static: P–δ at 1000 mm/s is within 1 % of 200 mm/s before
    /// the peak (2000: 3 %, 4000: 6 %), measured on the default panel.
    double speed = 1000.0;
    double deltaMax = 0.0;         ///< mm (0: twice the block thickness, past the push-out)
    double timeStepSafety = 0.3;   ///< dt = safety·2·sqrt(m/K) for the stiffest expected contact

    std::vector<Formulation> formulations = {Formulation::Adapted, Formulation::Original};
    /// Stage 1: SDP refined (coarse to fine) at VDP = fixedVdp, every formulation.
    std::vector<double> sdps = {1.0, 0.7, 0.5, 0.35, 0.25};
    /// The SDPs at which the per-node formulations (original, single-node) run (empty: all
    /// of sdps): their time step shrinks as 1/sqrt(N), so their finest runs cost the most.
    std::vector<double> originalSdps = {1.0, 0.7, 0.5, 0.35};
    double fixedVdp = 0.05;
    /// Stage 2 (adapted): VDP refined (coarse to fine) at the converged SDP of stage 1.
    std::vector<double> vdps = {0.4, 0.2, 0.14, 0.1, 0.05};
    bool twoWay = true;            ///< false: stage 1 only
    /// A run is converged when its P(δ) differs from the finest run's by at most this
    /// (slabCurveDifference: loading branch and peak, relative to the finest run's peak force)
    /// and it fails the same way (slabFailureMode).
    double tolerance = 0.05;
    std::vector<double> snapshotDeltas;  ///< δ of the snapshots, mm (empty: 6 from 0 to δ_max)
    int samples = 200;             ///< P–δ rows per run

    std::string outDir = "results/slab";
    bool plots = true;
    bool quiet = false;
    bool writeScene = true;        ///< slab_scene.toml + assets for lsdem-run
};

/// The resolved stiffnesses (N and mm) of a study.
struct SlabStiffness
{
    double knStar = 0.0, ksStar = 0.0;   ///< adapted (and volume), N/mm³
    double kn = 0.0, ks = 0.0;           ///< original (and single-node), N/mm
};

/// Check @a o; throw Error naming the option and the fix.
void checkSlabStudyOptions(const SlabStudyOptions& o);

/// The stiffnesses the study uses, with defaults filled in (see the file comment).
SlabStiffness slabStiffness(const SlabStudyOptions& o);

/// The contact model of blocks with each other, the frame and the indenter.
ContactModel slabContactModel(const SlabStudyOptions& o, Formulation formulation);

/// Bake the panel's one block shape: level set at @a vdp, nodes by isotropic remeshing at
/// @a sdp (sharp edges kept), areas from the mesh.
std::shared_ptr<const GrainAsset> bakeSlabBlock(const SlabPanel& panel, double vdp, double sdp);

/// The scene of one run: the panel's blocks (free), the frame (level-set obstacles of the
/// same asset, fixed), the indenter (a sphere touching the central block's top, moving down at
/// o.speed) and the contact models, with the block asset (@a block, as saved at @a assetPath)
/// posed from its principal frame. The time step is @a dt and the run ends when the indenter
/// has moved δ_max.
Scene makeSlabScene(const SlabStudyOptions& o, Formulation formulation, const GrainAsset& block,
                    const std::string& assetPath, double dt);

/// The scene as a commented TOML file that lsdem-run reads (asset paths relative to
/// @a sceneDir when they lie below it).
std::string slabSceneToml(const Scene& scene, const SlabStudyOptions& o,
                          const std::string& sceneDir);

/// dt = safety·2·sqrt(m/K), K the stiffness of the stiffest expected contact: a block pressed
/// between its two x neighbours, 2·kn*·A_shared (adapted), 2·kn·N_shared (original, N_shared
/// the nodes on a shared face).
double slabTimeStep(const SlabStudyOptions& o, const SlabPanel& panel, const GrainAsset& block,
                    Formulation formulation);

/// One point of a P–δ curve.
struct SlabSample
{
    double delta = 0.0;       ///< indenter displacement, mm
    double force = 0.0;       ///< P, the blocks' force on the indenter (upward), N
    double centralDrop = 0.0; ///< downward displacement of the central block, mm
    double othersMax = 0.0;   ///< largest displacement of any other block, mm
    double frameForce = 0.0;  ///< upward force of the frame on the blocks, N
    double kinetic = 0.0;     ///< kinetic energy, N·mm
};

/// Every block's state at one δ.
struct SlabSnapshot
{
    double delta = 0.0;
    std::vector<Vec3> displacement;      ///< of each block's centre, mm
    std::vector<std::array<SlabFace, 6>> faces;  ///< each block's faces, posed
};

struct SlabRunResult
{
    Formulation formulation = Formulation::Adapted;
    double sdp = 0.0, vdp = 0.0;
    int nodes = 0;                 ///< nodes per block
    double meanSpacing = 0.0;      ///< measured mean nearest-node distance, mm
    double stiffness = 0.0;        ///< kn* or kn
    double dt = 0.0;
    double stabilityLimit = 0.0;   ///< smallest stable step the simulation saw (its check)
    long long steps = 0;
    double bakeSeconds = 0.0, runSeconds = 0.0;
    long long nodeChecks = 0;      ///< nodes considered over the run
    std::vector<SlabSample> curve;
    std::vector<SlabSnapshot> snapshots;
    std::vector<Vec3> finalDisplacement;  ///< of each block at δ_max
    bool stopped = false;          ///< ended early (error below)
    std::string error;
};

/// Run one case: the panel with @a block (baked at (sdp, vdp), saved at @a assetPath) under
/// formulation @a f. @a progress, if set, is called now and then with δ.
SlabRunResult runSlabCase(const SlabStudyOptions& o, const SlabPanel& panel,
                          std::shared_ptr<const GrainAsset> block, const std::string& assetPath,
                          Formulation f, double sdp, double vdp,
                          const std::function<void(double delta)>& progress = {});

/// The difference between two P–δ curves, relative to the peak P of @a b: the root mean square
/// of P_a − P_b at the δ of @a b (P_a interpolated) up to the δ of b's peak (the loading
/// branch), or the difference of the peaks, whichever is larger. With @a wholeCurve, the root
/// mean square over all δ instead (the drop after the peak is a block falling out: dynamic, and
/// slower to converge).
double slabCurveDifference(const std::vector<SlabSample>& a, const std::vector<SlabSample>& b,
                           bool wholeCurve = false);

/// How the panel ended up at δ_max.
enum class SlabFailureMode {
    None,             ///< no result
    PushOut,          ///< the central block went down by more than δ/2 and every other block
                      ///< moved less than a quarter of that and less than t/3 (Mirkhalaf et al.)
    BlocksDisplaced,  ///< other blocks moved more than t/3 and stayed (blocks sticking together)
    Deflection,       ///< the panel deflects as a whole, no block pushed out
};
SlabFailureMode slabFailureMode(const SlabPanel& panel, const SlabRunResult& run);
std::string slabFailureModeName(SlabFailureMode mode);

/// A text account of how the panel failed at δ_max: which blocks moved, how far.
std::string slabFailureSummary(const SlabPanel& panel, const SlabRunResult& run);

struct SlabStudyResult
{
    std::vector<SlabRunResult> runs;
    std::vector<std::string> stage;   ///< per run: "sdp", "vdp" or "coarse" (where it was first run)
    /// The refinement series, coarse to fine, as run indices: stage 1 per formulation (SDP at
    /// the fixed VDP) and stage 2 (VDP at the converged SDP; its run at the fixed VDP is shared
    /// with stage 1).
    std::map<Formulation, std::vector<int>> sdpSeries;
    std::vector<int> vdpSeries;
    double convergedSdp = 0.0, convergedVdp = 0.0;
    bool sdpConverged = false, vdpConverged = false;
    int coarseRun = -1, convergedRun = -1;   ///< runs shown in the snapshots
    double wallSeconds = 0.0;
};

/// The converged run of a refinement series (@a series: indices into @a runs, coarse to fine):
/// the coarsest run from which on every finer one ran to the end, fails the same way as the
/// finest (push-out, blocks displaced or deflection: the paper's Sec. 3.5) and is within
/// @a tolerance of it (slabCurveDifference). The finest alone proves nothing: @a converged is
/// false when no coarser run agrees (the finest is returned), -1 for an empty series.
int slabConvergedRun(const SlabPanel& panel, const std::vector<SlabRunResult>& runs,
                     const std::vector<int>& series, double tolerance, bool& converged);

/// A forecast of the study's cost, printed before it starts.
struct SlabCostEstimate
{
    int runs = 0;
    double nodesPerBlockFinest = 0.0;
    long long steps = 0;              ///< summed over runs
    double seconds = 0.0;             ///< on this machine's cores, roughly; at most
    double secondsAtLeast = 0.0;      ///< the same if stage 2 converges at the coarsest SDP
    double memoryBytes = 0.0;         ///< the largest single run
    std::string text;
};
SlabCostEstimate estimateSlabCost(const SlabStudyOptions& o);

/// Limits of checkSlabStudyOptions: a study over them is refused (the quick default is 1.6e5
/// steps and about 0.1 GiB; the seed's resolution, one run, 9.3e3 steps and 0.8 GiB).
constexpr long long kMaxSlabSteps = 1000000000LL;
constexpr double kMaxSlabMemoryBytes = 20.0 * 1073741824.0;

/// The whole study. Writes only the baked blocks (o.outDir/assets/block_sdp*_vdp*.vdb, read by
/// the runs' scenes); progress goes to @a log if not null; @a afterEachRun, if set, sees the
/// result so far after every run (lsdem-study writes the outputs there, so that a study cut
/// short keeps its finished runs). See writeSlabOutputs.
SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun = {});

/// Write slab.csv, slab_runs.csv, slab_snapshots.csv and slab_failure.txt into o.outDir
/// (each atomically).
void writeSlabOutputs(const SlabStudyResult& result, const SlabStudyOptions& o,
                      const SlabPanel& panel);

/// The quick default and the `--full` lists of the two-way study.
SlabStudyOptions slabFullOptions();

/// The indenter's travel: o.deltaMax, or twice the thickness when that is 0.
double slabDeltaMax(const SlabStudyOptions& o);

} // namespace lsdem
