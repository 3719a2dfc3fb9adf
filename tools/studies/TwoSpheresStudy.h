/// @file TwoSpheresStudy.h
/// @brief The two-sphere central-compression benchmark (Feldfogel et al. 2024, Fig. 1 and 3):
///        two equal spheres, grain 0 fixed, grain 1 moved along the centre line by δ; the
///        force P on the centre line at each δ, per formulation, node count and stiffness,
///        averaged over random orientations of both spheres. Displacement control: no dynamics.
#pragma once

#include "studies/RunDistributor.h"
#include "studies/SphereSeriesOptions.h"

#include "lsdem/contact/NodeContact.h"

#include <string>
#include <vector>

namespace lsdem {

/// The two-sphere defaults: N = 500 … 16000, k series at N ≈ 8000, voxel 0.05 mm,
/// δ up to 0.1 mm in `steps` steps, three orientations.
struct TwoSpheresOptions : SphereSeriesOptions
{
    TwoSpheresOptions() { outDir = "results/two-spheres"; }
    int steps = 10;  ///< δ steps from 0 to deltaMax
};

/// The paper's base stiffness of @a f in N and mm: kn = 1 GN/mm for original and single-node,
/// kn* = 1 GPa/mm = 1e3 N/mm³ for adapted, kv = 1e3 N/mm³ for volume.
double defaultStiffness(Formulation f);

/// One row of results: one formulation, node count, stiffness and δ.
struct TwoSpheresRow
{
    Formulation formulation;
    int nodesRequested = 0;
    double nodesActual = 0;     ///< nodes of the baked sphere
    double stiffness = 0;
    double delta = 0;
    double forceMean = 0, forceStd = 0, forceMin = 0, forceMax = 0;  ///< over orientations
    /// NormalModel::continuumSphereForce at this stiffness: the limit of a law per area
    /// (SCIENCE.md §3); the others' forces diverge from it as the nodes refine
    double forceExact = 0;
};

struct TwoSpheresResult
{
    std::vector<TwoSpheresRow> rows;
    NodeCheckStats stats;
    double bakeSeconds = 0, contactSeconds = 0;
};

/// Check @a o and throw Error naming the bad option and the fix.
void checkTwoSpheresOptions(const TwoSpheresOptions& o);

/// What the run of one node count takes on 2 cores of this machine, seconds: the sphere's
/// bake (sphereBakeSeconds), then its contacts.
double twoSpheresRunSeconds(const TwoSpheresOptions& o, int nodes);
/// The plan printed before the runs: what is baked and pressed, and the time it will take (on
/// @a ranks ranks of 2 cores, the runs handed out largest first).
std::string twoSpheresPlanText(const TwoSpheresOptions& o, int ranks);

/// Run the study (no files written), one run per node count spread by @a ranks. On rank 0 the
/// result, the same on any number of ranks; the other ranks do the runs rank 0 hands them and
/// get an empty result.
TwoSpheresResult runTwoSpheres(const TwoSpheresOptions& o,
                               RunDistributor& ranks = serialRunDistributor());

/// Write @a result as CSV to @a path (atomically).
void writeTwoSpheresCsv(const TwoSpheresResult& result, const TwoSpheresOptions& o,
                        const std::string& path);

} // namespace lsdem
