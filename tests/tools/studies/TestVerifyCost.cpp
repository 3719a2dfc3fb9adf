// The estimates printed before the verification suite and the sphere studies (VerifyCost.h,
// SphereBakeCost.h, TwoSpheresStudy.h): they count what the runs will do, the laws each case
// runs, the ball's bake once, and the silo's discharges from Beverloo's law. (Whether they hold
// on this machine is measured, not tested: docs/verification.md#cost, docs/cube27.md#cost.)
#include "studies/SphereBakeCost.h"
#include "studies/TwoSpheresStudy.h"
#include "studies/verify/VerifyCases.h"
#include "studies/verify/VerifyCost.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace lsdem;
using namespace lsdem::verify;

namespace {

double partOf(const VerifyEstimate& e, const std::string& name)
{
    for (const VerifyEstimate::Part& p : e.parts)
        if (p.name == name) return p.seconds;
    return -1.0;
}

} // namespace

TEST(VerifyCost, ListsExactlyTheCasesTheSuiteRunsInItsOrder)
{
    VerifyOptions all;
    std::vector<std::string> run;
    for (const CaseEntry& c : caseList())
        if (runsCase(all, c)) run.push_back(c.name);
    const VerifyEstimate e = estimateVerification(all);
    ASSERT_EQ(e.parts.size(), run.size() + 1);  // and the ball's bake, first
    EXPECT_EQ(e.parts[0].name, "the ball's bake");
    for (size_t i = 0; i < run.size(); ++i) EXPECT_EQ(e.parts[i + 1].name, run[i]);
    EXPECT_EQ(partOf(e, "silo"), -1.0);  // run only when named

    double sum = 0.0;
    for (const VerifyEstimate::Part& p : e.parts) {
        EXPECT_GT(p.seconds, 0.0) << p.name;
        sum += p.seconds;
    }
    EXPECT_DOUBLE_EQ(e.seconds, sum);

    // A box alone bakes no ball.
    VerifyOptions box;
    box.cases = {"incline"};
    const VerifyEstimate b = estimateVerification(box);
    ASSERT_EQ(b.parts.size(), 1u);
    EXPECT_EQ(b.parts[0].name, "incline");
}

TEST(VerifyCost, ACaseCostsOnlyForTheLawsItRuns)
{
    const std::vector<Formulation>& every = allFormulations();
    VerifyOptions all;
    const VerifyEstimate e = estimateVerification(all);
    for (size_t i = 0; i < every.size(); ++i) {
        VerifyOptions one;
        one.formulations = {every[i]};
        const VerifyEstimate a = estimateVerification(one);
        for (const CaseEntry& c : caseList()) {
            if (!runsCase(all, c)) continue;
            // A law the case does not run costs it nothing; one it runs, something.
            EXPECT_EQ(c.cost.perLaw[i] > 0.0, caseRunsLaw(c.laws, every[i]) &&
                                                  c.laws != CaseLaws::Own)
                << c.name << " " << formulationName(every[i]);
            EXPECT_GE(partOf(a, c.name), c.cost.fixed) << c.name;
            EXPECT_LE(partOf(a, c.name), partOf(e, c.name)) << c.name;
            if (!caseRunsLaw(c.laws, every[i])) {
                EXPECT_DOUBLE_EQ(partOf(a, c.name), c.cost.fixed) << c.name;
            }
        }
    }
}

TEST(VerifyCost, TheBallsCasesFollowItsNodesAndTheQuickVersionIsQuicker)
{
    VerifyOptions base, fine, quick;
    fine.setup.sphereNodes = 2 * base.setup.sphereNodes;
    quick.quick = true;
    const VerifyEstimate b = estimateVerification(base), f = estimateVerification(fine),
                         q = estimateVerification(quick);
    EXPECT_NEAR(partOf(f, "spin-wall"), std::sqrt(2.0) * partOf(b, "spin-wall"), 1e-12);  // ∝ √N
    EXPECT_DOUBLE_EQ(partOf(f, "incline"), partOf(b, "incline"));  // a box, not the ball
    EXPECT_GT(partOf(f, "the ball's bake"), partOf(b, "the ball's bake"));
    EXPECT_LT(q.seconds, b.seconds);
    EXPECT_GT(partOf(q, "silo"), 0.0);  // the quick version runs a small silo
}

TEST(VerifyCost, TheSilosDischargesFollowBeverloosFlow)
{
    // The duration of a discharge is the grains counted over Beverloo's flow ∝ (D − k·d)^2.5:
    // a larger orifice empties sooner.
    VerifyOptions small, large;
    small.cases = large.cases = {"silo"};
    small.siloGrains = large.siloGrains = {"spheres"};
    small.siloOrifices = {5.0};
    large.siloOrifices = {8.0};
    const auto [smallLeast, smallMost] = siloDischargeSeconds(small);
    const auto [largeLeast, largeMost] = siloDischargeSeconds(large);
    EXPECT_LT(largeLeast, smallLeast);
    // What the two differ by is the discharges alone (the same packing and settling), in
    // the ratio of the flows: (8 − 1.5)^2.5 / (5 − 1.5)^2.5 = 4.7 for spheres (k 1.5).
    VerifyOptions both = small;
    both.siloOrifices = {5.0, 8.0};
    const auto [bothLeast, bothMost] = siloDischargeSeconds(both);
    const double fill = smallLeast + largeLeast - bothLeast;  // packing and settling
    EXPECT_GT(fill, 0.0);
    EXPECT_NEAR((smallLeast - fill) / (largeLeast - fill), std::pow(6.5 / 3.5, 2.5), 1e-9);
    EXPECT_LT(bothLeast, bothMost);  // the packing's margin

    // Sand as well costs more; a wider silo holds more grains and costs more.
    VerifyOptions sand = small, wide = small;
    sand.siloGrains = {"spheres", "sand"};
    wide.siloRadius = 15.0;
    EXPECT_GT(siloDischargeSeconds(sand).first, smallLeast);
    EXPECT_GT(siloDischargeSeconds(wide).first, 2.0 * smallLeast);

    // And the suite's estimate carries the silo's range.
    const VerifyEstimate e = estimateVerification(both);
    EXPECT_DOUBLE_EQ(e.siloLeast, bothLeast);
    EXPECT_DOUBLE_EQ(e.siloMost, bothMost);
}

TEST(SphereStudiesCost, BakesGrowWithVoxelsAndNodesAndEveryRunIsCounted)
{
    EXPECT_GT(sphereBakeSeconds(5.0, 0.05, 4000), sphereBakeSeconds(5.0, 0.1, 4000));
    EXPECT_GT(sphereBakeSeconds(5.0, 0.1, 8000), 2.0 * sphereBakeSeconds(5.0, 0.1, 4000) - 1e-3);
    // Half the voxel, eight times the voxels: the level set's part grows eightfold.
    const double grid = sphereBakeSeconds(5.0, 0.1, 0), fine = sphereBakeSeconds(5.0, 0.05, 0);
    EXPECT_NEAR(fine / grid, 8.0, 1e-9);

    TwoSpheresOptions o;
    o.nodeCounts = {1000, 4000};
    const std::string plan = twoSpheresPlanText(o, 1);
    EXPECT_NE(plan.find("2 spheres baked"), std::string::npos) << plan;
    EXPECT_NE(plan.find("up to 4000 nodes"), std::string::npos) << plan;
    EXPECT_GT(twoSpheresRunSeconds(o, 4000), sphereBakeSeconds(o.radius, o.voxel, 4000));
    // More orientations and steps: more contacts to evaluate.
    TwoSpheresOptions more = o;
    more.orientations *= 10;
    more.steps *= 10;
    EXPECT_GT(twoSpheresRunSeconds(more, 4000), twoSpheresRunSeconds(o, 4000));
    // Two ranks: the larger run's time at least, less than the sum.
    const std::string ranks = twoSpheresPlanText(o, 2);
    EXPECT_NE(ranks.find("on 2 ranks"), std::string::npos) << ranks;
}

TEST(VerifyCost, EstimatePrintsThePlanWithoutRunningOrWriting)
{
    lsdem::test::ScratchDir dir;
    const auto r = lsdem::test::runCommand(std::string(LSDEM_STUDY_EXE) +
                                           " verify --case silo --estimate --out '" + dir.file("x") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("verify plan: about "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(silo "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("running silo"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
}
