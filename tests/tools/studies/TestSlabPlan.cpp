// What a slab study runs and what it will cost (tools/studies/SlabPlan, SlabCost): the --seed
// preset down to the seed's resolution, its number of steps from the closed-form time step,
// and its time on N MPI ranks from the largest-first schedule; `--seed --estimate` prints it
// without running.
#include "studies/SlabStudy.h"

#include "support/TestSupport.h"

#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace lsdem;
using lsdem::test::runCommand;

namespace {

std::vector<double> sdpsOf(const std::vector<SlabCase>& cases)
{
    std::vector<double> v;
    for (const SlabCase& c : cases) v.push_back(c.sdp);
    return v;
}

std::vector<double> vdpsOf(const std::vector<SlabCase>& cases)
{
    std::vector<double> v;
    for (const SlabCase& c : cases) v.push_back(c.vdp);
    return v;
}

double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

} // namespace

// The adapted formulation only, SDP from 1 mm to the seed's 0.06 mm at the seed's VDP
// 0.025 mm, then VDP from 0.4 mm down to 0.025 mm at the converged SDP, in steps of about
// sqrt 2 both ways (rounded: 0.09/0.06 = 1.5), and the coarse case of the snapshots.
TEST(SlabPlan, SeedPresetRefinesTheAdaptedFormulationToTheSeedsResolution)
{
    const SlabStudyOptions o = slabSeedOptions();
    EXPECT_NO_THROW(checkSlabStudyOptions(o));
    const std::vector<SlabCase> one = slabStageOneCases(o);
    for (const SlabCase& c : one) {
        EXPECT_EQ(c.formulation, Formulation::Adapted);
        EXPECT_EQ(c.vdp, 0.025);
    }
    EXPECT_EQ(sdpsOf(one), (std::vector<double>{1, 0.7, 0.5, 0.35, 0.25, 0.18, 0.125, 0.09, 0.06}));
    const std::vector<SlabCase> two = slabStageTwoCases(o, 0.06);
    for (const SlabCase& c : two) EXPECT_EQ(c.sdp, 0.06);
    EXPECT_EQ(vdpsOf(two), (std::vector<double>{0.4, 0.28, 0.2, 0.14, 0.1, 0.07, 0.05, 0.035, 0.025}));
    for (const std::vector<double>& series : {sdpsOf(one), vdpsOf(two)})
        for (size_t i = 1; i < series.size(); ++i)
            EXPECT_NEAR(series[i - 1] / series[i], std::sqrt(2.0), 0.09) << series[i];  // two digits
    const SlabCase coarse = slabCoarseCase(o);
    EXPECT_EQ(coarse.sdp, 1.0);
    EXPECT_EQ(coarse.vdp, 0.4);
}

// Runs: 9 of stage 1, 8 of stage 2 (its VDP 0.025 run is stage 1's) and the coarse case.
// The adapted time step does not depend on the discretization: dt = 0.3·2·sqrt(m/(2·kn*·A))
// for a block of mass m = ρ(L²t − tan²θ·t³/3) squeezed over the shared hexagon
// A = (L − h)·t/cosθ, h = tanθ·t/2, kn* = E/L; every run has ceil(δ_max/(v·dt)) steps.
// On N ranks: one rank is the serial estimate, a rank per run leaves the longest run of each
// stage, and ranks of 4 cores take half as long as ranks of 2.
TEST(SlabPlan, SeedEstimateFromTheTimeStepAndTheSchedule)
{
    const SlabStudyOptions o = slabSeedOptions();
    const SlabCostEstimate e = estimateSlabCost(o);
    EXPECT_EQ(e.runs, 18);
    EXPECT_EQ(e.stageOne.size(), 9u);
    EXPECT_EQ(e.stageTwoMost.size(), 9u);  // 8 VDPs and the coarse case

    const double L = o.panel.blockSize, t = o.panel.thickness;
    const double tanTheta = std::tan(o.panel.angleDeg * kPi / 180.0), h = tanTheta * t / 2.0;
    const double mass = o.material.density * (L * L * t - tanTheta * tanTheta * t * t * t / 3.0);
    const double area = (L - h) * t / std::cos(o.panel.angleDeg * kPi / 180.0);
    const double dt = o.timeStepSafety * 2.0 * std::sqrt(mass / (2.0 * (o.material.youngModulus / L) * area));
    const long long steps = static_cast<long long>(std::ceil(2.0 * t / (o.speed * dt)));
    EXPECT_EQ(e.steps, 18 * steps);

    const double sum = std::accumulate(e.stageOne.begin(), e.stageOne.end(), 0.0) +
                       std::accumulate(e.stageTwoMost.begin(), e.stageTwoMost.end(), 0.0);
    EXPECT_NEAR(e.seconds, sum, 1e-9 * sum);
    EXPECT_NEAR(slabSecondsOnRanks(e, 1, 2.0, true), e.seconds, 1e-9 * e.seconds);
    EXPECT_NEAR(slabSecondsOnRanks(e, 1, 2.0, false), e.secondsAtLeast, 1e-9 * e.seconds);
    const double longest = largest(e.stageOne) + largest(e.stageTwoMost);
    EXPECT_NEAR(slabSecondsOnRanks(e, 9, 2.0, true), longest, 1e-9 * longest);
    EXPECT_NEAR(slabSecondsOnRanks(e, 64, 2.0, true), longest, 1e-9 * longest);
    EXPECT_NEAR(slabSecondsOnRanks(e, 9, 4.0, true), longest / 2.0, 1e-9 * longest);
    // More ranks never take longer.
    for (int n = 1; n < 12; ++n)
        EXPECT_GE(slabSecondsOnRanks(e, n, 2.0, true), slabSecondsOnRanks(e, n + 1, 2.0, true)) << n;

    // The text says it: on one process, what a rank per run would take under mpirun; under
    // mpirun, what these ranks take.
    EXPECT_NE(e.text.find("18 runs"), std::string::npos) << e.text;
    EXPECT_NE(e.text.find("under mpirun, 9 ranks"), std::string::npos) << e.text;
    const SlabCostEstimate onFour = estimateSlabCost(o, 4, 2.0);
    EXPECT_NE(onFour.text.find("on 4 MPI ranks x 2 cores"), std::string::npos) << onFour.text;
}

TEST(SlabPlan, ProgramPrintsTheSeedEstimateWithoutRunning)
{
    lsdem::test::ScratchDir dir;
    const auto r = runCommand(std::string(LSDEM_STUDY_EXE) + " slab --seed --estimate --out '" +
                              dir.file("x") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("cost: 18 runs"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("under mpirun, 9 ranks of 2 cores"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
    // --seed and --full are two presets: one at a time.
    const auto both = runCommand(std::string(LSDEM_STUDY_EXE) + " slab --seed --full --estimate");
    EXPECT_EQ(both.exitCode, 1) << both.output;
    EXPECT_NE(both.output.find("--seed"), std::string::npos) << both.output;
}

// A list option given twice keeps its last list, as a single value's last occurrence wins (a
// script may override an option by appending it); CLI11 joined the two lists. One run here:
// SDP 0.5 alone and adapted alone.
TEST(SlabPlan, ARepeatedListOptionKeepsItsLastList)
{
    const std::string base = std::string(LSDEM_STUDY_EXE) +
                             " slab --blocks 3 --vdp-fixed 0.5 --no-two-way --estimate";
    const auto once = runCommand(base + " --sdp 0.5 --formulation adapted");
    ASSERT_EQ(once.exitCode, 0) << once.output;
    EXPECT_NE(once.output.find("cost: 1 runs"), std::string::npos) << once.output;
    const auto twice = runCommand(base + " --sdp 1 0.7 --sdp 0.5 --formulation adapted original "
                                         "--formulation adapted");
    ASSERT_EQ(twice.exitCode, 0) << twice.output;
    EXPECT_EQ(twice.output.substr(twice.output.find("cost:")),
              once.output.substr(once.output.find("cost:")));
    // An empty value is still refused, not taken for the boundary between two lists.
    for (const char* values : {"''", "1 '' 0.5", "'' 0.5"}) {
        const auto empty = runCommand(base + " --sdp " + values);
        EXPECT_EQ(empty.exitCode, 1) << values << ": " << empty.output;
        EXPECT_NE(empty.output.find("--sdp wants a number, got ''"), std::string::npos)
            << values << ": " << empty.output;
    }
}
