// Tests of eliminateSamples: the count asked for, and a spread between a random subset's and
// the hexagonal packing's.
#include "lsdem/core/Error.h"
#include "lsdem/mesh/SampleElimination.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using lsdem::Vec3;

namespace {

/// Uniform random points in the unit square (z = 0).
std::vector<Vec3> squarePoints(int count, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) points.emplace_back(unit(random), unit(random), 0.0);
    return points;
}

/// Each point's distance to its nearest other point: {least, mean}.
std::pair<double, double> nearestDistances(const std::vector<Vec3>& points)
{
    double least = std::numeric_limits<double>::infinity(), sum = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < points.size(); ++j)
            if (j != i) nearest = std::min(nearest, (points[j] - points[i]).norm());
        least = std::min(least, nearest);
        sum += nearest;
    }
    return {least, sum / double(points.size())};
}

/// That @a chosen, of @a candidates on a unit area, are @a kept distinct indices in
/// increasing order whose points spread evenly. References for N points on unit area
/// (a = 1/√N): a random subset (a Poisson process) has a mean nearest distance of a/2 and a
/// least one near zero; the hexagonal packing has both at a·√(2/√3) = 1.075a. Yuksel reports
/// about 0.8 of the packing's spacing for five candidates a point; the square's edges (points
/// there lack neighbours outside) add a little. So: well above random, at most the packing.
void expectEvenlySpread(const std::vector<Vec3>& candidates, const std::vector<int>& chosen,
                        int kept)
{
    ASSERT_EQ(chosen.size(), size_t(kept));
    EXPECT_TRUE(std::is_sorted(chosen.begin(), chosen.end()));
    EXPECT_EQ(std::adjacent_find(chosen.begin(), chosen.end()), chosen.end());
    std::vector<Vec3> points;
    for (int i : chosen) points.push_back(candidates[size_t(i)]);
    const auto [least, mean] = nearestDistances(points);
    const double a = 1.0 / std::sqrt(double(kept));
    EXPECT_GT(mean, 0.8 * a);
    EXPECT_LE(mean, 1.075 * a);
    EXPECT_GT(least, 0.4 * a);
}

TEST(SampleElimination, KeepsTheCountAskedForSpreadEvenly)
{
    const int kept = 1000;
    const std::vector<Vec3> candidates = squarePoints(5 * kept, 5);
    expectEvenlySpread(candidates, lsdem::eliminateSamples(candidates, kept, 1.0), kept);

    const double a = 1.0 / std::sqrt(double(kept));
    const std::vector<Vec3> randomSubset(candidates.begin(), candidates.begin() + kept);
    const auto [randomLeast, randomMean] = nearestDistances(randomSubset);
    EXPECT_LT(randomMean, 0.6 * a);  // (the reference's own check: a random subset is not even)
    EXPECT_LT(randomLeast, 0.1 * a);
}

TEST(SampleElimination, SpreadsEvenlyWhereNeighboursLieFarApartInTheBins)
{
    // The neighbour lists keep each neighbour as its step from the point in the bins' order
    // (cell by cell, z slowest): 2 bytes unless some step needs more. Two layers of 35,000
    // points over the unit square, a fiftieth of a cell apart in z but in two slices of cells
    // (a point below the square sets where the cells start), put every point's neighbours in
    // the other layer about 35,000 places away, beyond 2 bytes. The kept points must still
    // spread as evenly as KeepsTheCountAskedForSpreadEvenly's (one surface, ten candidates a
    // point here).
    const int kept = 7000;
    const double reach = 2.0 * std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * kept));
    const double cell = std::max(reach, 1.0 / 128.0);  // (PointBins: at most 128 cells a side)
    std::vector<Vec3> candidates = squarePoints(35000, 7);
    for (Vec3 p : squarePoints(35000, 8)) candidates.push_back(p + Vec3(0.0, 0.0, 0.02 * cell));
    candidates.emplace_back(0.5, 0.5, -0.99 * cell);
    expectEvenlySpread(candidates, lsdem::eliminateSamples(candidates, kept, 1.0), kept);
}

TEST(SampleElimination, RefusesACountItCannotKeep)
{
    const std::vector<Vec3> candidates = squarePoints(10, 1);
    EXPECT_THROW(lsdem::eliminateSamples(candidates, 11, 1.0), lsdem::Error);
    EXPECT_THROW(lsdem::eliminateSamples(candidates, 0, 1.0), lsdem::Error);
    EXPECT_THROW(lsdem::eliminateSamples(candidates, 5, 0.0), lsdem::Error);
}

} // namespace
