/// @file SlabCost.h
/// @brief What a slab study will cost (runs, steps, time on this machine and on N MPI ranks,
///        peak memory), printed before it starts and used to refuse absurd studies.
#pragma once

#include "studies/SlabPlan.h"

#include <string>
#include <vector>

namespace lsdem {

/// What one run costs.
struct SlabRunCost
{
    double nodes = 0.0;     ///< per block
    long long steps = 0;
    double seconds = 0.0;   ///< wall time on 2 cores (this machine's), roughly
    double bytes = 0.0;     ///< peak memory: the bake, then the run
};
SlabRunCost slabRunCost(const SlabStudyOptions& o, const SlabCase& c);

/// A forecast of the study's cost, printed before it starts.
struct SlabCostEstimate
{
    int runs = 0;
    double nodesPerBlockFinest = 0.0;
    long long steps = 0;              ///< summed over runs
    double seconds = 0.0;             ///< on this machine's cores, roughly; at most
    double secondsAtLeast = 0.0;      ///< the same if stage 2 converges at the coarsest SDP
    double memoryBytes = 0.0;         ///< the largest single run (per rank, under MPI)
    /// Each run's seconds on 2 cores, by batch: stage 1; stage 2 with the coarse case when
    /// stage 2 runs at the finest SDP (most) and at the coarsest (least). Stage 2 starts when
    /// stage 1 is done: it needs stage 1's converged SDP.
    std::vector<double> stageOne, stageTwoMost, stageTwoLeast;
    std::string text;
};

/// The estimate, its text saying what @a ranks MPI ranks of @a coresPerRank cores each take
/// (with one rank: what one rank of 2 cores per run would take under mpirun).
SlabCostEstimate estimateSlabCost(const SlabStudyOptions& o, int ranks = 1,
                                  double coresPerRank = 2.0);

/// The study's wall time on @a ranks ranks of @a coresPerRank cores each (threads scale
/// linearly from the 2 cores measured), each stage's runs handed out largest first; stage 2
/// at the finest SDP if @a most, else at the coarsest.
double slabSecondsOnRanks(const SlabCostEstimate& e, int ranks, double coresPerRank, bool most);

} // namespace lsdem
