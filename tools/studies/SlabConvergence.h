/// @file SlabConvergence.h
/// @brief When a refinement series of the slab study has converged: the difference between two
///        P–δ curves, and the coarsest run that agrees with the finest.
#pragma once

#include "studies/SlabRun.h"

#include <vector>

namespace lsdem {

/// The difference between two P–δ curves, relative to the peak P of @a b: the root mean square
/// of P_a − P_b at the δ of @a b (P_a interpolated) up to the δ of b's peak (the loading
/// branch), or the difference of the peaks, whichever is larger. With @a wholeCurve, the root
/// mean square over all δ instead (the drop after the peak is a block falling out: dynamic, and
/// slower to converge).
double slabCurveDifference(const std::vector<SlabSample>& a, const std::vector<SlabSample>& b,
                           bool wholeCurve = false);

/// The converged run of a refinement series (@a series: indices into @a runs, coarse to fine):
/// the coarsest run from which on every finer one ran to the end, fails the same way as the
/// finest (push-out, blocks displaced or deflection: the paper's Sec. 3.5) and is within
/// @a tolerance of it (slabCurveDifference). The finest alone proves nothing: @a converged is
/// false when no coarser run agrees (the finest is returned), -1 for an empty series.
int slabConvergedRun(const SlabPanel& panel, const std::vector<SlabRunResult>& runs,
                     const std::vector<int>& series, double tolerance, bool& converged);

} // namespace lsdem
