/// @file TwoSpheresStudy.h
/// @brief The two-sphere central-compression benchmark (Feldfogel et al. 2024, Fig. 1 and 3):
///        two equal spheres, grain 0 fixed, grain 1 moved along the centre line by δ; the
///        force P on the centre line at each δ, per formulation, node count and stiffness,
///        averaged over random orientations of both spheres. Displacement control: no dynamics.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/NodeContact.h"

#include <string>
#include <vector>

namespace lsdem {

struct TwoSpheresOptions
{
    std::vector<Formulation> formulations = {Formulation::Original, Formulation::Adapted};
    std::vector<int> nodeCounts = {500, 1000, 2000, 4000, 8000, 16000};
    /// Stiffness multipliers of each formulation's base stiffness for the k series, run at the
    /// node count closest to kSeriesNodes (the full N sweep runs at the base stiffness).
    std::vector<double> stiffnessFactors = {0.25, 0.5, 0.75, 1.0};
    std::vector<double> stiffness;  ///< explicit stiffnesses for every formulation (overrides)
    int kSeriesNodes = 8000;
    double radius = 5.0;            ///< mm
    double voxel = 0.05;            ///< mm
    double deltaMax = 0.1;          ///< mm
    int steps = 10;
    int orientations = 3;
    unsigned seed = 1;
    NodeTesting testing = NodeTesting::Symmetric;
    std::string outDir = "results/two-spheres";
    bool plots = true;
    bool quiet = false;
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
    double forceExact = 0;      ///< continuum limit of the adapted formulation (SCIENCE.md §3)
};

struct TwoSpheresResult
{
    std::vector<TwoSpheresRow> rows;
    NodeCheckStats stats;
    double bakeSeconds = 0, contactSeconds = 0;
};

/// Check @a o and throw Error naming the bad option and the fix.
void checkTwoSpheresOptions(const TwoSpheresOptions& o);

/// Run the study (no files written).
TwoSpheresResult runTwoSpheres(const TwoSpheresOptions& o);

/// Write @a result as CSV to @a path (atomically).
void writeTwoSpheresCsv(const TwoSpheresResult& result, const TwoSpheresOptions& o,
                        const std::string& path);

} // namespace lsdem
