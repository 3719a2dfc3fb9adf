// The triaxial study's cost estimate (TriaxialCost.h): the consolidation's steps follow the
// walls' travel from the cloud's void ratio, the time scales with the nodes and the threads, and
// the printed table lists every run and the total. (Whether it holds on this machine is
// measured, not tested: docs/triaxial.md#cost.)
#include "studies/TriaxialCost.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

namespace {

TriaxialRunPlan plan()
{
    TriaxialRunPlan p;
    p.name = "adapted SDP 0.05 seed 1";
    p.grains = 1000;
    p.nodesPerGrain = 1700.0;
    p.timeStep = 2e-6;
    p.startVoidRatio = 7.3;
    p.approachRate = 100.0;
    p.settledSteps = 2000;
    p.shearSteps = 18000;
    return p;
}

} // namespace

TEST(TriaxialCost, TheConsolidationFollowsTheWallsTravel)
{
    const TriaxialRunPlan p = plan();
    const TriaxialRunCost c = triaxialRunCost(p, 2);
    EXPECT_EQ(c.shearSteps, p.shearSteps);
    // From e 7.3 to 0.46 each size shrinks to (1.46/8.3)^(1/3) = 0.56 of its start: 0.44 of it
    // at 100/s of the start per second, 2e-6 s a step: about 2200 steps, then the ramp and hold.
    const double approach = (1.0 - std::cbrt(1.46 / 8.3)) / (100.0 * 2e-6);
    EXPECT_NEAR(double(c.consolidationSteps - p.settledSteps), approach, 2000.0);
    EXPECT_GT(c.consolidationSteps, p.settledSteps + 2000);

    // Half the step: twice the approach's steps.
    TriaxialRunPlan fine = p;
    fine.timeStep = 1e-6;
    const TriaxialRunCost f = triaxialRunCost(fine, 2);
    EXPECT_NEAR(double(f.consolidationSteps - c.consolidationSteps), approach, 2.0);

    // A cloud already as dense as the consolidated sample: only the ramp and the hold.
    TriaxialRunPlan dense = p;
    dense.startVoidRatio = 0.3;
    const TriaxialRunCost d = triaxialRunCost(dense, 2);
    EXPECT_LT(d.consolidationSteps, c.consolidationSteps);
    EXPECT_GT(d.consolidationSteps, dense.settledSteps);
}

TEST(TriaxialCost, TimeGrowsWithNodesAndShrinksWithThreads)
{
    const double coarse = triaxialStepSeconds(1000, 430.0, 2);
    const double fine = triaxialStepSeconds(1000, 4800.0, 2);
    EXPECT_GT(fine, 3.0 * coarse);                                    // mostly the nodes
    EXPECT_LT(fine, 4800.0 / 430.0 * coarse);                         // a part per grain
    EXPECT_GE(triaxialStepSeconds(2000, 430.0, 2), 2.0 * coarse);  // at least per grain
    const double one = triaxialStepSeconds(1000, 430.0, 1);
    EXPECT_GT(one, 1.5 * coarse);
    EXPECT_LT(one, 2.0 * coarse);
    const TriaxialRunCost c = triaxialRunCost(plan(), 2);
    const double step = triaxialStepSeconds(1000, 1700.0, 2);
    EXPECT_NEAR(c.seconds, double(c.consolidationSteps + c.shearSteps) * step, 1e-9 * c.seconds);
    // At most: the hold at σ₃ broken twice.
    EXPECT_NEAR(c.secondsAtMost - c.seconds, 2.0 * 2000 * step, 1e-9 * c.seconds);
}

TEST(TriaxialCost, TheTableListsEachRunAndTheTotal)
{
    TriaxialRunPlan second = plan();
    second.name = "original SDP 0.05 seed 1";
    second.shearSteps = 30000;
    const std::string text = describeTriaxialCost({plan(), second}, 2, 1);
    EXPECT_NE(text.find("adapted SDP 0.05 seed 1"), std::string::npos) << text;
    EXPECT_NE(text.find("original SDP 0.05 seed 1"), std::string::npos) << text;
    EXPECT_NE(text.find("in all about"), std::string::npos) << text;
    EXPECT_EQ(text.find("ranks"), std::string::npos) << "one process: no ranks line";
    const std::string spread = describeTriaxialCost({plan(), second}, 2, 2);
    EXPECT_NE(spread.find("on 2 ranks, largest runs first"), std::string::npos) << spread;
}

// A membrane run: the walls' consolidation of the whole sample, then the cylinder's grains
// (fewer, part of them next to the membrane, whose nodes cost more) consolidated again and
// sheared. Fails if the membrane's stage were left out (as it was until 2026-11-29) or costed
// at the whole sample's grains.
TEST(TriaxialCost, AMembraneRunCostsTheWallsStageThenTheCylindersInTheMembrane)
{
    TriaxialRunPlan walls = plan();
    walls.nodesPerGrain = 431.0;
    TriaxialRunPlan membrane = walls;
    membrane.membrane = true;
    const TriaxialRunCost w = triaxialRunCost(walls, 2), m = triaxialRunCost(membrane, 2);
    // 1000 grains: the cylinder keeps about 541 (as measured), 206 of them within a diameter
    // of a membrane 4.7 diameters in radius.
    EXPECT_NEAR(m.keptGrains, 541.0, 15.0);
    EXPECT_NEAR(m.grainsAtMembrane, 541.0 * (1.0 - std::pow(1.0 - 1.0 / 4.71, 2)), 10.0);
    EXPECT_EQ(m.consolidationSteps, w.consolidationSteps + m.membraneSteps);
    EXPECT_GT(m.membraneSteps, 2000);
    const double wallStep = triaxialStepSeconds(1000.0, 431.0, 2);
    const double membraneStep = membraneStepSeconds(m.keptGrains, m.grainsAtMembrane, 431.0, 2);
    EXPECT_GT(membraneStep, triaxialStepSeconds(m.keptGrains, 431.0, 2));
    EXPECT_NEAR(m.seconds,
                double(w.consolidationSteps) * wallStep +
                    double(m.membraneSteps + m.shearSteps) * membraneStep,
                1e-9 * m.seconds);
    // At most: the shearing done twice over and some of it once more.
    EXPECT_GT(m.secondsAtMost, m.seconds + 2.0 * double(m.shearSteps) * membraneStep);
    // A tall sample (twice as high as wide) is narrower for its grains: more of them lie next
    // to the membrane.
    TriaxialRunPlan tall = membrane;
    tall.heightRatio = 2.0;
    const TriaxialRunCost t = triaxialRunCost(tall, 2);
    EXPECT_GT(t.grainsAtMembrane / t.keptGrains, m.grainsAtMembrane / m.keptGrains);
}
