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

#include "studies/SlabConvergence.h"
#include "studies/RunDistributor.h"
#include "studies/SlabCost.h"
#include "studies/SlabFailure.h"
#include "studies/SlabModel.h"
#include "studies/SlabOptions.h"
#include "studies/SlabPlan.h"
#include "studies/SlabRun.h"
#include "studies/SlabScene.h"

#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace lsdem {

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

/// The whole study, its runs spread by @a ranks (each stage's runs largest first; stage 2
/// starts when stage 1 is done). Writes only the baked blocks (o.outDir/assets/
/// block_sdp*_vdp*.vdb, for lsdem-run; the runs use them from memory); progress goes to @a log
/// if not null; @a afterEachRun, if set, sees the result so far after every run (lsdem-study
/// writes the outputs there, so that a study cut short keeps its finished runs). See
/// writeSlabOutputs. The result is the same on any number of ranks, in the same order; it is
/// rank 0's, and only rank 0 writes (blocks made elsewhere come to it as bytes); the other
/// ranks do the runs rank 0 hands them and get an empty result.
SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun = {},
                             RunDistributor& ranks = serialRunDistributor());

/// Write slab.csv, slab_runs.csv, slab_snapshots.csv and slab_failure.txt into o.outDir
/// (each atomically).
void writeSlabOutputs(const SlabStudyResult& result, const SlabStudyOptions& o,
                      const SlabPanel& panel);

} // namespace lsdem
