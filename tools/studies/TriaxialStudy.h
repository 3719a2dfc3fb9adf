/// @file TriaxialStudy.h
/// @brief The triaxial study: the same sample (the meshes of --meshes on the same lattice,
///        consolidated to σ₃) tested with each formulation at each node spacing (SDP), the
///        voxel size (VDP) fixed, on one sample per seed. Adapted should converge as the SDP shrinks; original, whose
///        kn is per node, stiffens instead. Each run is independent, so under MPI the runs are
///        spread over the ranks (RunDistributor.h).
#pragma once

#include "studies/TriaxialCost.h"
#include "studies/TriaxialOptions.h"
#include "studies/TriaxialTest.h"

#include <functional>
#include <string>
#include <vector>

namespace lsdem {

class RunDistributor;

struct TriaxialRun
{
    Formulation formulation = Formulation::Adapted;
    double sdp = 0.0, vdp = 0.0;
    long long seed = 1;            ///< the sample's seed
    double nodesPerGrain = 0.0;    ///< mean over the meshes
    double stiffness = 0.0;        ///< kn* (N/mm³) or kn (N/mm)
    double dt = 0.0;
    double stabilityLimit = 0.0;   ///< the smallest stable step the simulation saw
    double strainRate = 0.0;       ///< ε̇ of the shearing, 1/s
    TriaxialPath path = TriaxialPath::Compression;
    TriaxialTestResult test;
    double bakeSeconds = 0.0, runSeconds = 0.0;
    double msPerStep = 0.0;        ///< wall time per step of the whole test
};

struct TriaxialStudyResult
{
    /// formulations in the order given, each SDP coarsest first, each seed in the order given
    std::vector<TriaxialRun> runs;
    int meshes = 0;
    long long grains = 0;
    double spacing = 0.0;           ///< of the starting lattice, mm
    double meanDiameter = 0.0;      ///< equivalent diameter of the meshes, mm
};

/// Run the study, its runs spread by @a ranks (rank 0 returns every run; the other ranks only
/// do the runs they are handed and return an empty result). @a onRun, if set, is told each run
/// on rank 0 as it arrives; @a progress, if set, each row of the runs done on rank 0; @a onPlan,
/// if set, every run's plan (for the cost estimate, TriaxialCost.h) before the first starts.
/// @throw Error for bad options or meshes, or a run that failed.
TriaxialStudyResult runTriaxialStudy(
    const TriaxialOptions& o, RunDistributor& ranks,
    const std::function<void(const TriaxialRun&)>& onRun = {},
    const std::function<void(Formulation, double sdp, long long seed, const TriaxialRow&)>&
        progress = {},
    const std::function<void(const std::vector<TriaxialRunPlan>&)>& onPlan = {});

/// ε̇ from the inertial number: I = ε̇·d·sqrt(ρ/σ₃).
double triaxialStrainRate(const TriaxialOptions& o, double meanDiameter);

} // namespace lsdem
