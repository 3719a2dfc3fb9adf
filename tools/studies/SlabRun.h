/// @file SlabRun.h
/// @brief One run of the slab study: the panel pushed by the indenter to δ_max, its P–δ curve,
///        the panel's state at chosen δ (snapshots) and where every block ended up.
#pragma once

#include "studies/SlabOptions.h"

#include "lsdem/ls/GrainAsset.h"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lsdem {

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

/// Run one case: the panel with @a block (baked at (sdp, vdp)) under formulation @a f.
/// @a progress, if set, is called now and then with δ.
SlabRunResult runSlabCase(const SlabStudyOptions& o, const SlabPanel& panel,
                          std::shared_ptr<const GrainAsset> block, Formulation f, double sdp,
                          double vdp, const std::function<void(double delta)>& progress = {});

} // namespace lsdem
