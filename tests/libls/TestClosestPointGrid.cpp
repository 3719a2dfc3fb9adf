// Tests of ClosestPointGrid: the closest point it finds is the one a look at every triangle
// finds, for points near the surface, inside it and far outside its box, on meshes fine and
// coarse against the cells; and bad input is refused.
#include "lsdem/ls/ClosestPointGrid.h"
#include "lsdem/ls/Error.h"
#include "lsdem/ls/TriangleOffset.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

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
    std::mt19937_64 rng(3);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int n = 0; n < 3000; ++n) {
        const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const double r = n % 3 == 0   ? 0.99 + 0.02 * uniform(rng)
                         : n % 3 == 1 ? uniform(rng)
                                      : 1.0 + 2.0 * uniform(rng);
        const Vec3 p = r * direction;
        const Vec3 fast = grid.closestPoint(p), slow = closestByEveryTriangle(mesh, p);
        // The same point, or (on an edge or corner two triangles share) one as near.
        ASSERT_NEAR((fast - p).norm(), (slow - p).norm(), 1e-14) << "at " << p.transpose();
        ASSERT_LT((fast - slow).norm(), 1e-12) << "at " << p.transpose();
    }
}

} // namespace

TEST(ClosestPointGrid, FindsWhatEveryTriangleFindsOnAFineMesh)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(4);  // 5120 triangles, edges ≈ 0.06
    expectSameAsEveryTriangle(sphere, 0.1);
    expectSameAsEveryTriangle(sphere, 0.02);  // cells smaller than the triangles
}

TEST(ClosestPointGrid, FindsWhatEveryTriangleFindsOnACoarseMesh)
{
    const TriangleMesh sphere = lsdem::test::makeIcosphere(1);  // 80 triangles
    expectSameAsEveryTriangle(sphere, 0.05);  // the cell budget widens the cells
    expectSameAsEveryTriangle(sphere, 5.0);   // one cell holds everything
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
}
