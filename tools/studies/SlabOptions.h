/// @file SlabOptions.h
/// @brief What a slab study runs: the panel, its material, the contact stiffnesses, the
///        indenter and the SDP/VDP series, with the checks made before anything runs. Units: mm,
///        N, s, tonne (so stresses in MPa = N/mm²).
#pragma once

#include "studies/SlabPanel.h"
#include "studies/StudyLimits.h"

#include "lsdem/contact/ContactModel.h"

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

/// Check @a o; throw Error naming the option and the fix.
void checkSlabStudyOptions(const SlabStudyOptions& o);

/// Limits of checkSlabStudyOptions: a study over them is refused (the quick default is 1.6e5
/// steps and about 0.1 GiB; the seed's resolution, one run, 9.3e3 steps and 0.8 GiB).
constexpr long long kMaxSlabSteps = kMaxStudySteps;
constexpr double kMaxSlabMemoryBytes = 20.0 * 1073741824.0;

/// The quick default and the `--full` lists of the two-way study.
SlabStudyOptions slabFullOptions();

/// `--seed`: the adapted formulation's two-way study down to the seed's resolution
/// (SDP 0.06 mm, VDP 0.025 mm; Feldfogel et al. 2024): SDP 1 ... 0.06 mm in steps of about
/// sqrt 2 at VDP 0.025 mm, then VDP 0.4 ... 0.025 mm likewise at the converged SDP.
SlabStudyOptions slabSeedOptions();

/// The indenter's travel: o.deltaMax, or twice the thickness when that is 0.
double slabDeltaMax(const SlabStudyOptions& o);

/// @a v sorted coarse to fine (largest first), duplicates dropped.
std::vector<double> slabCoarseToFine(std::vector<double> v);

/// Whether stage 1 runs formulation @a f at node spacing @a sdp: the per-node formulations
/// (original, single-node) only at o.originalSdps when given (their time step shrinks with the
/// node count, so their finest runs cost the most).
bool slabStageOneRuns(const SlabStudyOptions& o, Formulation f, double sdp);

/// The indenter displacements of the snapshots: o.snapshotDeltas sorted, or six from 0 to δ_max.
std::vector<double> slabSnapshotDeltas(const SlabStudyOptions& o);

} // namespace lsdem
