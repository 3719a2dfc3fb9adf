/// @file TriaxialCost.h
/// @brief What a triaxial study will cost, printed before its first run: each run's steps
///        (the consolidation's, from how far the walls must close, and the shearing's, from
///        the path, the strain rate and the time step) times a step's cost on this machine
///        (per grain and per grain node, measured), and the study's wall time on its ranks.
#pragma once

#include <string>
#include <vector>

namespace lsdem {

/// What one run needs to be costed: the sample, its resolution and its plan.
struct TriaxialRunPlan
{
    std::string name;              ///< "adapted SDP 0.05"
    long long grains = 0;
    double nodesPerGrain = 0.0;
    double timeStep = 0.0;         ///< s
    double startVoidRatio = 0.0;   ///< of the cloud before consolidation
    double approachRate = 100.0;   ///< the walls' closing rate at first, 1/s
    long long settledSteps = 2000; ///< the consolidation's hold at σ₃
    long long shearSteps = 0;
    /// --boundary membrane: after the walls' consolidation, a cylinder of the sample is cut,
    /// wrapped in a membrane, consolidated again and sheared (TriaxialMembrane.h).
    bool membrane = false;
    double heightRatio = 1.0;      ///< the sample's height over its width
};

/// One run's estimate.
struct TriaxialRunCost
{
    long long consolidationSteps = 0, shearSteps = 0;
    /// In a membrane: the steps of its consolidation (included in consolidationSteps), the
    /// grains the cylinder keeps and those of them next to the membrane.
    long long membraneSteps = 0;
    double keptGrains = 0.0, grainsAtMembrane = 0.0;
    double seconds = 0.0;          ///< wall time with the study's threads
    /// The same if the consolidation's hold at σ₃ is broken twice and starts again (two of
    /// sixteen runs measured consolidated in about 10,000 steps, the others in 5400–7500);
    /// in a membrane also if the shearing's step is halved (its steps done twice over and
    /// some of them wasted: 1000 grains to 20 % measured it).
    double secondsAtMost = 0.0;
};

/// The void ratio a frictionless consolidation of the sand grains ends at (0.45–0.47 measured
/// at σ₃ 100 kPa): where the consolidation's steps are counted to.
inline constexpr double kConsolidatedVoidRatio = 0.46;

/// The estimate of one run on @a threads threads (of this machine's kind).
TriaxialRunCost triaxialRunCost(const TriaxialRunPlan& plan, int threads);

/// Seconds a step of @a grains grains of @a nodesPerGrain nodes takes on @a threads threads.
double triaxialStepSeconds(double grains, double nodesPerGrain, int threads);

/// The same for @a grains grains in a membrane, @a grainsAtMembrane of them next to it (their
/// nodes are tested against its triangles).
double membraneStepSeconds(double grains, double grainsAtMembrane, double nodesPerGrain,
                           int threads);

/// The table printed before the runs: each run's steps and minutes, and the study's wall time
/// on @a ranks ranks (runs handed out largest first).
std::string describeTriaxialCost(const std::vector<TriaxialRunPlan>& plans, int threads,
                                 int ranks);

} // namespace lsdem
