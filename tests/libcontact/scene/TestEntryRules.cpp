// The rules of single entries' numbers (EntryRules.h): a density and an orientation are refused
// in the same words by a scene file, a grains table, validateScene and Python, and a grains
// table allows the looser norm of poses printed with fewer digits.
#include "lsdem/scene/EntryRules.h"

#include "lsdem/core/NumberText.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

TEST(EntryRules, DensityAndOrientationSayWhatIsWrong)
{
    EXPECT_EQ(densityProblem(-2.0), "must be >= 0 (got -2)");
    EXPECT_FALSE(densityProblem(0.0));
    EXPECT_TRUE(densityProblem(std::nan("")));

    EXPECT_FALSE(orientationProblem(Quat::Identity()));
    EXPECT_EQ(orientationProblem(Quat(0, 0, 0, 0)), "is not a rotation (zero quaternion)");
    EXPECT_EQ(orientationProblem(Quat(1, 1, 0, 0)), "is not a unit quaternion (norm " +
                                                        numberText(std::sqrt(2.0)) + ")");
    // 5e-5 off unit: too far for a scene, close enough for a printed table.
    const Quat printed(1.0 + 5e-5, 0, 0, 0);
    EXPECT_TRUE(orientationProblem(printed));
    EXPECT_FALSE(orientationProblem(printed, kTableOrientationTolerance));
    EXPECT_TRUE(orientationProblem(Quat(std::nan(""), 0, 0, 0), kTableOrientationTolerance));
}
