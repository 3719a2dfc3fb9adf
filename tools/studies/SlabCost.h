/// @file SlabCost.h
/// @brief What a slab study will cost (runs, steps, time on this machine, peak memory), printed
///        before it starts and used to refuse absurd studies.
#pragma once

#include "studies/SlabOptions.h"

#include <string>

namespace lsdem {

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

} // namespace lsdem
