// NumberRange: each range holds what its words say, at its ends and just past them, and never
// NaN or an infinity.
#include "lsdem/core/NumberRange.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace lsdem;

TEST(NumberRange, EachRangeHoldsWhatItsWordsSay)
{
    const double below1 = std::nextafter(1.0, 0.0), above0 = std::nextafter(0.0, 1.0);
    struct Row
    {
        NumberRange range;
        const char* words;
        double in[2], out[2];
    };
    const Row rows[] = {
        {NumberRange::Finite, "finite", {-1e300, 0.0}, {}},
        {NumberRange::Positive, "> 0", {above0, 1e300}, {0.0, -1.0}},
        {NumberRange::NonNegative, ">= 0", {0.0, 2.0}, {-above0, -1.0}},
        {NumberRange::Fraction, "in [0, 1)", {0.0, below1}, {1.0, -above0}},
        {NumberRange::PositiveFraction, "in (0, 1]", {above0, 1.0}, {0.0, std::nextafter(1.0, 2.0)}},
    };
    for (const Row& r : rows) {
        EXPECT_EQ(numberRangeText(r.range), r.words);
        for (double v : r.in) EXPECT_TRUE(inNumberRange(r.range, v)) << r.words << " " << v;
        if (r.range != NumberRange::Finite) {
            for (double v : r.out) EXPECT_FALSE(inNumberRange(r.range, v)) << r.words << " " << v;
        }
        for (double v : {std::nan(""), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()})
            EXPECT_FALSE(inNumberRange(r.range, v)) << r.words << " " << v;
    }
    // The words every check of a user's number uses.
    EXPECT_EQ(outOfRange(NumberRange::Fraction, 1.0), "must be in [0, 1) (got 1)");
    EXPECT_EQ(outOfRange(NumberRange::Positive, -0.5), "must be > 0 (got -0.5)");
    EXPECT_FALSE(outOfRange(NumberRange::NonNegative, 0.0));
}
