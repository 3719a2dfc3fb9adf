// Tests of ClosestPointGrid: the closest point it finds is the one a look at every triangle
// finds, for points near the surface, inside it and far outside its box, on meshes fine and
// coarse against the cells; and bad input is refused.
#include "lsdem/mesh/ClosestPointGrid.h"
#include "lsdem/core/Error.h"
#include "lsdem/mesh/TriangleOffset.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <random>
#include <vector>

using lsdem::ClosestPointGrid;
using lsdem::TriangleMesh;
using lsdem::Vec3;

namespace {

/// The reference: every triangle tried, the nearest kept (the first of equals).
Vec3 closestByEveryTriangle(const TriangleMesh& mesh, const Vec3& p)
{
    double best = std::numeric_limits<double>::infinity();
    Vec3 offset = Vec3::Zero();
    for (const auto& t : mesh.triangles) {
        const Vec3 o = lsdem::offsetFromTriangle(p, mesh.vertices[size_t(t[0])],
                                                 mesh.vertices[size_t(t[1])],
                                                 mesh.vertices[size_t(t[2])]);
        if (o.squaredNorm() < best) {
            best = o.squaredNorm();
            offset = o;
        }
    }
    return p - offset;
}

/// Points in shells around the unit sphere: within 1 % of it (as a remesher's vertices are),
/// deep inside, and up to three times its size away (outside the grid's box).
void expectSameAsEveryTriangle(const TriangleMesh& mesh, double cellSize)
{
    const ClosestPointGrid grid(mesh.vertices, mesh.triangles, cellSize);
    const ClosestPointGrid view(mesh, cellSize);  // over the mesh, not a copy of it
    std::mt19937_64 rng(3);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int n = 0; n < 3000; ++n) {
        const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const double r = n % 3 == 0   ? 0.99 + 0.02 * uniform(rng)
                         : n % 3 == 1 ? uniform(rng)
                                      : 1.0 + 2.0 * uniform(rng);
        const Vec3 p = r * direction;
        // The same triangle wins (ties to the lower index), so the same bits.
        const Vec3 expected = closestByEveryTriangle(mesh, p);
        ASSERT_EQ(grid.closestPoint(p), expected) << "at " << p.transpose();
        ASSERT_EQ(view.closestPoint(p), expected) << "at " << p.transpose();
    }
}

} // namespace

TEST(ClosestPointGrid, FindsWhatEveryTriangleFindsOnAFineMesh)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(4);  // 5120 triangles, edges ≈ 0.06
    expectSameAsEveryTriangle(sphere, 0.1);
    expectSameAsEveryTriangle(sphere, 0.2);
}

TEST(ClosestPointGrid, FindsWhatEveryTriangleFindsOnACoarseMesh)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(1);  // 80 triangles
    expectSameAsEveryTriangle(sphere, 0.05);  // cells smaller than the triangles (widened a bit)
    expectSameAsEveryTriangle(sphere, 5.0);   // one cell holds everything
}

// Points where several triangles are equally near: on a box's planes of symmetry, at its
// corners and edges, at face centres (each face is two triangles), and just off them.
TEST(ClosestPointGrid, BreaksTiesAsALookAtEveryTriangleDoes)
{
    const TriangleMesh box = lsdem::test::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    const ClosestPointGrid grid(box.vertices, box.triangles, 0.3);
    const double coordinates[] = {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5};
    for (double x : coordinates)
        for (double y : coordinates)
            for (double z : coordinates) {
                const Vec3 p(x, y, z);
                ASSERT_EQ(grid.closestPoint(p), closestByEveryTriangle(box, p))
                    << "at " << p.transpose();
            }
}

// With labels a query keeps to its own: the top face's triangles (label 1) give the nearest
// point of the top face even from just above the bottom one.
TEST(ClosestPointGrid, KeepsToTheTrianglesOfALabel)
{
    const TriangleMesh box = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    std::vector<int> labels;
    for (const auto& t : box.triangles) {
        const bool top = box.vertices[size_t(t[0])].z() == 1.0 &&
                         box.vertices[size_t(t[1])].z() == 1.0 &&
                         box.vertices[size_t(t[2])].z() == 1.0;
        labels.push_back(top ? 1 : 0);
    }
    const ClosestPointGrid grid(box.vertices, box.triangles, 0.25, labels);
    const Vec3 p(0.3, 0.6, 0.05);
    EXPECT_LT((grid.closestPoint(p, 1) - Vec3(0.3, 0.6, 1.0)).norm(), 1e-15);
    EXPECT_LT((grid.closestPoint(p, 0) - Vec3(0.3, 0.6, 0.0)).norm(), 1e-15);
    EXPECT_LT((grid.closestPoint(p) - Vec3(0.3, 0.6, 0.0)).norm(), 1e-15);
    EXPECT_EQ(grid.closestPoint(p, 7), p);  // no triangle has that label
}

// Zero-area triangles mixed in are left out; on a closed surface their points are on the
// edges of triangles with area, so the distance found is the same.
TEST(ClosestPointGrid, LeavesOutZeroAreaTriangles)
{
    TriangleMesh sphere = lsdem::test::makeIcosphere(2);
    const size_t n = sphere.triangles.size();
    for (size_t k = 0; k < n; k += 7) {
        const std::array<int, 3> t = sphere.triangles[k];  // a copy: the vector grows
        sphere.triangles.push_back({t[0], t[1], t[0]});  // an edge, twice
    }
    const ClosestPointGrid grid(sphere.vertices, sphere.triangles, 0.2);
    std::mt19937_64 rng(9);
    std::normal_distribution<double> gauss;
    for (int k = 0; k < 500; ++k) {
        const Vec3 p(gauss(rng), gauss(rng), gauss(rng));
        EXPECT_NEAR((grid.closestPoint(p) - p).norm(),
                    (closestByEveryTriangle(sphere, p) - p).norm(), 1e-15);
    }
}

TEST(ClosestPointGrid, KeepsToAFewCellsPerTriangleWhateverTheCellAsked)
{
    const TriangleMesh box = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(100, 100, 0.01));
    const ClosestPointGrid grid(box.vertices, box.triangles, 1e-6);
    EXPECT_GT(grid.cellSize(), 1.0);  // 12 triangles do not get 10^22 cells
    const Vec3 p(30, 40, 5);
    EXPECT_LT((grid.closestPoint(p) - Vec3(30, 40, 0.01)).norm(), 1e-12);
}

TEST(ClosestPointGrid, RefusesBadInput)
{
    const TriangleMesh box = lsdem::test::makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    EXPECT_THROW(ClosestPointGrid(box.vertices, box.triangles, 0.0), lsdem::Error);
    EXPECT_THROW(ClosestPointGrid(box.vertices, box.triangles,
                                  std::numeric_limits<double>::quiet_NaN()),
                 lsdem::Error);
    EXPECT_THROW(ClosestPointGrid(box.vertices, {{0, 1, 99}}, 0.1), lsdem::Error);
    EXPECT_THROW(ClosestPointGrid(box.vertices, {}, 0.1), lsdem::Error);
    EXPECT_THROW(ClosestPointGrid(box.vertices, {{0, 0, 1}}, 0.1), lsdem::Error);  // no area
    EXPECT_THROW(ClosestPointGrid(box.vertices, box.triangles, 0.1, {1, 2}), lsdem::Error);
    std::vector<Vec3> notFinite = box.vertices;
    notFinite[3].y() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(ClosestPointGrid(notFinite, box.triangles, 0.1), lsdem::Error);
}
