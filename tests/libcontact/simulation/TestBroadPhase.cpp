// Broad phase: the cell grid finds exactly the pairs a brute-force O(n²) scan finds, sorted and
// without repeats, whatever the spread of the grains.
#include "lsdem/simulation/BroadPhase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

using namespace lsdem;

namespace {

using Pairs = std::vector<std::pair<int, int>>;

/// Every pair i < j whose spheres come within @a margin, by checking all of them.
Pairs bruteForcePairs(const std::vector<Vec3>& centers, const std::vector<double>& radii,
                      double margin)
{
    Pairs pairs;
    for (int i = 0; i < static_cast<int>(centers.size()); ++i)
        for (int j = i + 1; j < static_cast<int>(centers.size()); ++j) {
            const double reach = radii[i] + radii[j] + margin;
            if ((centers[i] - centers[j]).squaredNorm() <= reach * reach) pairs.emplace_back(i, j);
        }
    return pairs;  // generated in lexicographic order
}

void expectSortedUniqueOrdered(const Pairs& pairs)
{
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    EXPECT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end()) << "repeated pair";
    for (const auto& p : pairs) EXPECT_LT(p.first, p.second);
}

/// @a count spheres of radius in [rMin, rMax] in clusters: each cluster is a box of side
/// @a clusterSize around a centre drawn in [-spread, spread]³ (negative coordinates included).
void randomClusters(std::mt19937& rng, int count, int clusters, double clusterSize,
                    double spread, double rMin, double rMax, std::vector<Vec3>& centers,
                    std::vector<double>& radii)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0), radius(rMin, rMax);
    std::vector<Vec3> clusterCenters;
    for (int c = 0; c < clusters; ++c)
        clusterCenters.emplace_back(spread * unit(rng), spread * unit(rng), spread * unit(rng));
    std::uniform_int_distribution<int> pick(0, clusters - 1);
    for (int i = 0; i < count; ++i) {
        const Vec3 offset(unit(rng), unit(rng), unit(rng));
        centers.push_back(clusterCenters[pick(rng)] + 0.5 * clusterSize * offset);
        radii.push_back(radius(rng));
    }
}

} // namespace

// Dense random packings of mixed radii (a factor 10 between the smallest and the largest, so
// most cells hold spheres much smaller than the cell), with and without margin: the same list
// as the brute force. The densities are chosen so that a good fraction of the spheres overlap
// (the list is long, not trivially empty).
TEST(BroadPhase, MatchesBruteForceOnRandomMixedSpheres)
{
    for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
        std::mt19937 rng(seed);
        std::vector<Vec3> centers;
        std::vector<double> radii;
        randomClusters(rng, 400, 1, 35.0, 0.0, 0.3, 3.0, centers, radii);
        for (double margin : {0.0, 0.5}) {
            const Pairs found = findCandidatePairs(centers, radii, margin);
            const Pairs expected = bruteForcePairs(centers, radii, margin);
            EXPECT_GT(expected.size(), 200u) << "the test needs many overlapping pairs";
            EXPECT_EQ(found, expected) << "seed " << seed << ", margin " << margin;
            expectSortedUniqueOrdered(found);
        }
    }
}

// Clusters far apart, around the origin and at negative coordinates, with the grid's cells
// counted from the lowest centre: clusters 1e3 apart and clusters 1e8 apart (more than 2²¹
// cells per axis, where the packed cell keys wrap around; a wrapped key may put far grains in
// one bucket but must never lose a near pair).
TEST(BroadPhase, MatchesBruteForceForFarApartClustersAndNegativeCoordinates)
{
    for (double spread : {1e3, 1e8}) {
        for (unsigned seed : {11u, 12u, 13u}) {
            std::mt19937 rng(seed);
            std::vector<Vec3> centers;
            std::vector<double> radii;
            randomClusters(rng, 300, 6, 25.0, spread, 0.5, 2.5, centers, radii);
            // All negative: shift so that every coordinate is below zero.
            std::vector<Vec3> shifted = centers;
            for (Vec3& c : shifted) c -= Vec3::Constant(3.0 * spread);
            for (const auto* set : {&centers, &shifted}) {
                const Pairs found = findCandidatePairs(*set, radii, 0.1);
                const Pairs expected = bruteForcePairs(*set, radii, 0.1);
                EXPECT_GT(expected.size(), 50u);
                EXPECT_EQ(found, expected) << "spread " << spread << ", seed " << seed;
                expectSortedUniqueOrdered(found);
            }
        }
    }
}

// Edge cases: spheres that just touch (|c_i - c_j| = r_i + r_j exactly, in binary) count;
// a hair further apart they do not; coincident centres; no spheres or one sphere.
TEST(BroadPhase, TouchingCoincidentAndDegenerateInputs)
{
    EXPECT_TRUE(findCandidatePairs({}, {}).empty());
    EXPECT_TRUE(findCandidatePairs({Vec3(1, 2, 3)}, {1.0}).empty());

    // 0.5 + 1.5 = 2 exactly; the third sphere is 2 + 2⁻²⁰ from the second; the fourth sits on
    // the first's centre and is 2 from the second, 0.25 short of its reach.
    const std::vector<Vec3> centers = {Vec3(-1, 0, 0), Vec3(1, 0, 0),
                                       Vec3(1, 2.0 + std::ldexp(1.0, -20), 0),
                                       Vec3(-1, 0, 0)};
    const std::vector<double> radii = {0.5, 1.5, 0.5, 0.25};
    const Pairs found = findCandidatePairs(centers, radii);
    const Pairs expected = {{0, 1}, {0, 3}};
    EXPECT_EQ(found, expected);
    EXPECT_EQ(found, bruteForcePairs(centers, radii, 0.0));
    // A margin brings the third sphere in.
    const Pairs withMargin = findCandidatePairs(centers, radii, 1e-3);
    EXPECT_EQ(withMargin, bruteForcePairs(centers, radii, 1e-3));
    EXPECT_NE(std::find(withMargin.begin(), withMargin.end(), std::make_pair(1, 2)),
              withMargin.end());
}

// Equal spheres on a cubic lattice with spacing exactly the diameter: every face neighbour
// touches, nothing else does (diagonals are √2 diameters apart): n²·(n−1) pairs along each of
// the three axes of an n³ lattice.
TEST(BroadPhase, LatticeOfTouchingSpheresGivesTheFaceNeighbours)
{
    const int n = 6;
    std::vector<Vec3> centers;
    std::vector<double> radii;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                centers.emplace_back(2.0 * i - 5.0, 2.0 * j - 5.0, 2.0 * k - 5.0);
                radii.push_back(1.0);
            }
    const Pairs found = findCandidatePairs(centers, radii);
    EXPECT_EQ(found.size(), static_cast<size_t>(3 * n * n * (n - 1)));
    EXPECT_EQ(found, bruteForcePairs(centers, radii, 0.0));
}
