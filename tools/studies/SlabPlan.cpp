#include "studies/SlabPlan.h"

#include <tuple>

namespace lsdem {

bool SlabCase::operator<(const SlabCase& o) const
{
    return std::make_tuple(int(formulation), sdp, vdp) < std::make_tuple(int(o.formulation), o.sdp, o.vdp);
}

bool SlabCase::operator==(const SlabCase& o) const
{
    return formulation == o.formulation && sdp == o.sdp && vdp == o.vdp;
}

std::vector<SlabCase> slabStageOneCases(const SlabStudyOptions& o)
{
    std::vector<SlabCase> cases;
    for (double s : slabCoarseToFine(o.sdps))
        for (Formulation f : o.formulations)
            if (slabStageOneRuns(o, f, s)) cases.push_back({f, s, o.fixedVdp});
    return cases;
}

std::vector<SlabCase> slabStageTwoCases(const SlabStudyOptions& o, double sdp)
{
    std::vector<SlabCase> cases;
    if (!o.twoWay) return cases;
    for (double v : slabCoarseToFine(o.vdps)) cases.push_back({Formulation::Adapted, sdp, v});
    return cases;
}

SlabCase slabCoarseCase(const SlabStudyOptions& o)
{
    return {Formulation::Adapted, slabCoarseToFine(o.sdps).front(), slabCoarseToFine(o.vdps).front()};
}

} // namespace lsdem
