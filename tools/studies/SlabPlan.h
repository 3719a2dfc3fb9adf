/// @file SlabPlan.h
/// @brief The runs a slab study makes, in the order it makes them: stage 1 (SDP refined at the
///        fixed VDP, every formulation), stage 2 (VDP refined at the converged SDP, adapted)
///        and the coarse case of the snapshots. The study, its cost estimate and its tests
///        read the plan from here.
#pragma once

#include "studies/SlabOptions.h"

#include <vector>

namespace lsdem {

/// One run: a formulation at a discretization (mm).
struct SlabCase
{
    Formulation formulation = Formulation::Adapted;
    double sdp = 0.0, vdp = 0.0;
    bool operator<(const SlabCase& o) const;
    bool operator==(const SlabCase& o) const;
};

/// Stage 1: per SDP coarse to fine, each formulation that runs there (slabStageOneRuns), at
/// o.fixedVdp.
std::vector<SlabCase> slabStageOneCases(const SlabStudyOptions& o);

/// Stage 2 at the converged SDP @a sdp: adapted, VDP coarse to fine, o.fixedVdp included (the
/// study shares that run with stage 1). Empty without o.twoWay.
std::vector<SlabCase> slabStageTwoCases(const SlabStudyOptions& o, double sdp);

/// The coarse case of the snapshots (two-way studies): adapted, coarsest SDP and coarsest VDP.
SlabCase slabCoarseCase(const SlabStudyOptions& o);

} // namespace lsdem
