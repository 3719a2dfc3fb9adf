/// @file SphereSeriesOptions.h
/// @brief What the two sphere studies (two-spheres, cube27) have in common: equal spheres of
///        one radius baked at a series of node counts, run for each formulation at its base
///        stiffness, plus a stiffness series at one node count; random orientations averaged.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/NodeContact.h"
#include "lsdem/ls/GrainAsset.h"

#include <string>
#include <vector>

namespace lsdem {

struct SphereSeriesOptions
{
    std::vector<Formulation> formulations = {Formulation::Original, Formulation::Adapted};
    std::vector<int> nodeCounts = {500, 1000, 2000, 4000, 8000, 16000};
    /// Stiffness multipliers of each formulation's base stiffness for the k series, run at the
    /// node count closest to kSeriesNodes (the N sweep runs at the base stiffness).
    std::vector<double> stiffnessFactors = {0.25, 0.5, 0.75, 1.0};
    std::vector<double> stiffness;  ///< explicit stiffnesses for every formulation (overrides)
    int kSeriesNodes = 8000;
    double radius = 5.0;            ///< mm
    double voxel = 0.05;            ///< mm
    double deltaMax = 0.1;          ///< mm
    int orientations = 3;           ///< random orientation sets averaged
    unsigned seed = 1;
    NodeTesting testing = NodeTesting::Symmetric;
    std::string outDir;
    bool plots = true;
    bool quiet = false;
};

/// Check the shared options and throw Error naming the bad option and the fix.
void checkSphereSeriesOptions(const SphereSeriesOptions& o);

/// The node count of the stiffness series: the one of o.nodeCounts closest to o.kSeriesNodes.
int stiffnessSeriesNodes(const SphereSeriesOptions& o);

/// The study's sphere of radius o.radius baked at voxel o.voxel with about @a nodes nodes;
/// the bake's warnings are appended to @a warnings.
GrainAsset bakeSeriesSphere(const SphereSeriesOptions& o, int nodes, std::vector<std::string>& warnings);

} // namespace lsdem
