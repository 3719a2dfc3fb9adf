// The motions' names (GrainMotion.h), the one list scenes, grain tables and Python read: each
// name parses back to its motion, and nothing else parses.
#include "lsdem/simulation/GrainMotion.h"

#include <gtest/gtest.h>

using namespace lsdem;

TEST(GrainMotion, EachNameParsesBackAndNothingElseDoes)
{
    const std::vector<std::string> names = grainMotionNames();
    EXPECT_EQ(names, (std::vector<std::string>{"free", "fixed", "prescribed"}));
    for (GrainMotion m : {GrainMotion::Free, GrainMotion::Fixed, GrainMotion::Prescribed})
        EXPECT_EQ(parseGrainMotion(grainMotionName(m)), m);
    for (const char* other : {"", "Free", "fixed ", "moving"})
        EXPECT_FALSE(parseGrainMotion(other).has_value()) << other;
}
