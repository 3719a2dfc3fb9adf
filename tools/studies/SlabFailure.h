/// @file SlabFailure.h
/// @brief How the panel failed at the end of a run: push-out of the central block (as in the
///        experiments of Mirkhalaf et al. 2019), other blocks displaced, or deflection.
#pragma once

#include "studies/SlabRun.h"

#include <string>

namespace lsdem {

/// How the panel ended up at δ_max.
enum class SlabFailureMode {
    None,             ///< no result
    PushOut,          ///< the central block went down by more than δ/2 and every other block
                      ///< moved less than a quarter of that and less than t/3 (Mirkhalaf et al.)
    BlocksDisplaced,  ///< other blocks moved more than t/3 and stayed (blocks sticking together)
    Deflection,       ///< the panel deflects as a whole, no block pushed out
};
SlabFailureMode slabFailureMode(const SlabPanel& panel, const SlabRunResult& run);
std::string slabFailureModeName(SlabFailureMode mode);

/// A text account of how the panel failed at δ_max: which blocks moved, how far.
std::string slabFailureSummary(const SlabPanel& panel, const SlabRunResult& run);

} // namespace lsdem
