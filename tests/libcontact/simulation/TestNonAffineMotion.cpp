// D²min (NonAffineMotion.h) against closed forms: nil for any affine motion of a neighbourhood;
// n·|u|² for a grain moved by u off the affine field among n neighbours placed symmetrically
// about it (Σ D = 0, so the best J is the field's own); nil for a grain with three
// neighbours (any three independent offsets fix J exactly) and for one whose moved neighbour
// is its only one along an axis; and the neighbour search against every pair.
#include "lsdem/simulation/NonAffineMotion.h"

#include <gtest/gtest.h>

#include <random>

using namespace lsdem;

namespace {

/// A 3×3×3 lattice of spacing 1, grain (a, b, c) at index 9a + 3b + c.
std::vector<Vec3> lattice()
{
    std::vector<Vec3> x;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            for (int c = 0; c < 3; ++c) x.emplace_back(a, b, c);
    return x;
}

Mat3 someDeformation()
{
    Mat3 a;
    a << 1.02, 0.15, -0.03, 0.01, 0.97, 0.08, -0.05, 0.02, 1.1;
    return a;
}

} // namespace

TEST(NonAffineMotion, AnAffineMotionHasNone)
{
    std::mt19937 random(5);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2);
    std::vector<Vec3> reference = lattice();
    for (Vec3& x : reference) x += Vec3(jitter(random), jitter(random), jitter(random));
    const std::vector<std::vector<int>> near =
        neighboursWithin(reference, std::vector<double>(reference.size(), 0.6), 1.5);
    const Mat3 a = someDeformation();
    const Vec3 shift(3.0, -1.0, 0.5);
    std::vector<Vec3> current;
    for (const Vec3& x : reference) current.push_back(a * x + shift);
    const std::vector<double> d2 = nonAffineDisplacement(reference, current, near);
    for (size_t i = 0; i < d2.size(); ++i) {
        EXPECT_GE(near[i].size(), 3u) << i;
        EXPECT_LT(d2[i], 1e-24) << i;  // round-off of offsets of order 1
    }
}

TEST(NonAffineMotion, AGrainMovedOffTheFieldAmongSymmetricNeighboursHasNTimesItsSquare)
{
    const std::vector<Vec3> reference = lattice();
    // Radii 0.5 and reach 1.2: the face neighbours (distance 1) only, not the diagonals (√2).
    const std::vector<std::vector<int>> near =
        neighboursWithin(reference, std::vector<double>(reference.size(), 0.5), 1.2);
    const int centre = 13, corner = 0;
    ASSERT_EQ(near[size_t(centre)].size(), 6u);
    ASSERT_EQ(near[size_t(corner)].size(), 3u);
    const Mat3 a = someDeformation();
    const Vec3 u(0.03, -0.02, 0.05);
    std::vector<Vec3> current;
    for (const Vec3& x : reference) current.push_back(a * x);
    current[size_t(centre)] += u;
    const std::vector<double> d2 = nonAffineDisplacement(reference, current, near);
    EXPECT_NEAR(d2[size_t(centre)], 6.0 * u.squaredNorm(), 1e-14);
    // The corner's three neighbours fix a J that fits them exactly.
    EXPECT_LT(d2[size_t(corner)], 1e-26);
    // The centre's face neighbour (1, 1, 2) has it as its only neighbour along z: J's third
    // column takes the move in whole, and nothing is left (a lone direction is not measured).
    EXPECT_LT(d2[size_t(centre + 1)], 1e-26);
}

TEST(NonAffineMotion, NeighboursAreEveryPairWithinReach)
{
    std::mt19937 random(11);
    std::uniform_real_distribution<double> where(-3.0, 3.0), size(0.1, 0.6);
    std::vector<Vec3> centres;
    std::vector<double> radii;
    for (int i = 0; i < 300; ++i) {
        centres.emplace_back(where(random), where(random), where(random));
        radii.push_back(size(random));
    }
    const std::vector<std::vector<int>> near = neighboursWithin(centres, radii, 1.3);
    for (size_t i = 0; i < centres.size(); ++i) {
        std::vector<int> expected;
        for (size_t j = 0; j < centres.size(); ++j)
            if (j != i && (centres[j] - centres[i]).norm() < 1.3 * (radii[i] + radii[j]))
                expected.push_back(int(j));
        EXPECT_EQ(near[i], expected) << i;
    }
    EXPECT_TRUE(nonAffineDisplacement({}, {}, {}).empty());
}

// In a periodic cell a grain at a face has its neighbours across it: on a 4 × 4 × 4 lattice in
// a cell of 4 every grain has the same six, the cell stretched with its grains (an affine
// motion of the whole space) leaves D²min nil everywhere, and a grain moved off the field at
// a face gives its neighbours the same D²min as one moved inside gives its neighbours (the
// periodic lattice is the same from every grain), n·|u|² = 6·|u|² for the moved grain itself.
TEST(NonAffineMotion, APeriodicCellCountsNeighboursAcrossItsFaces)
{
    PeriodicCell cell;
    cell.size = Vec3(4, 4, 4);
    std::vector<Vec3> reference;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c) reference.emplace_back(a + 0.5, b + 0.5, c + 0.5);
    const size_t n = reference.size();
    const std::vector<double> radii(n, 0.5);
    const auto neighbours = neighboursWithin(reference, radii, 1.1, cell);
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(neighbours[i].size(), 6u) << i;

    const Vec3 stretch(1.05, 0.97, 0.9);
    std::vector<Vec3> stretched;
    for (const Vec3& x : reference) stretched.push_back(x.cwiseProduct(stretch));
    const Vec3 size = cell.size.cwiseProduct(stretch);
    for (double d : nonAffineDisplacement(reference, cell.size, stretched, size, neighbours))
        EXPECT_NEAR(d, 0.0, 1e-24);

    // Grain (1,1,1) inside and grain (0,1,1) at the x face, each moved by u on the stretched
    // field: the D²min of each grain round the moved one, taken one lattice step along x apart.
    const Vec3 u(0.03, -0.02, 0.01);
    const auto index = [](int a, int b, int c) { return size_t(16 * a + 4 * b + c); };
    std::vector<Vec3> inside = stretched, atFace = stretched;
    inside[index(1, 1, 1)] += u;
    atFace[index(0, 1, 1)] += u;
    const std::vector<double> dInside = nonAffineDisplacement(reference, cell.size, inside, size, neighbours);
    const std::vector<double> dFace = nonAffineDisplacement(reference, cell.size, atFace, size, neighbours);
    EXPECT_NEAR(dInside[index(1, 1, 1)], 6.0 * u.squaredNorm(), 1e-15);
    EXPECT_NEAR(dFace[index(0, 1, 1)], 6.0 * u.squaredNorm(), 1e-15);
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(dFace[index(a, b, c)], dInside[index((a + 1) % 4, b, c)], 1e-15)
                    << a << b << c;
    // Across the face: grain (3,1,1) is the moved grain's neighbour through its image.
    EXPECT_GT(dFace[index(3, 1, 1)], 0.1 * u.squaredNorm());

    // Without the cell the face grain has five neighbours, and its far neighbour sees nothing.
    const auto open = neighboursWithin(reference, radii, 1.1);
    EXPECT_EQ(open[index(0, 1, 1)].size(), 5u);
    EXPECT_LT(nonAffineDisplacement(reference, atFace, open)[index(3, 1, 1)], 1e-24);
}
