// Surface nodes: tributary areas, normals, spatial order and spacing statistics.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/SurfaceNodes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

using namespace lsdem;

TEST(SurfaceNodes, MeshAreasSumToTheMeshAreaAndNormalsPointOut)
{
    const TriangleMesh mesh = AnalyticShape::ellipsoid(2, 1, 0.5).surfaceMesh(0.15);
    const SurfaceNodes nodes = nodesFromMesh(mesh, AreaRule::Mesh);
    EXPECT_EQ(nodes.size(), mesh.vertices.size());
    EXPECT_NEAR(nodes.totalArea(), surfaceArea(mesh), 1e-12 * surfaceArea(mesh));
    for (size_t i = 0; i < nodes.size(); ++i) {
        EXPECT_NEAR(nodes.normals[i].norm(), 1.0, 1e-12);
        // Star-shaped about the origin: outward normals have a positive radial component.
        EXPECT_GT(nodes.normals[i].dot(nodes.positions[i]), 0.0);
    }
}

TEST(SurfaceNodes, CubeCornerNormalIsTheDiagonal)
{
    const TriangleMesh cube = AnalyticShape::box(1, 1, 1).surfaceMesh(0.5);
    const SurfaceNodes nodes = nodesFromMesh(cube, AreaRule::Mesh);
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes.positions[i].cwiseAbs().minCoeff() > 0.49) {  // a corner
            EXPECT_NEAR(nodes.normals[i].dot(nodes.positions[i].normalized()), 1.0, 1e-12);
        }
}

TEST(SurfaceNodes, SpatialSortIsAPermutationThatKeepsNeighboursClose)
{
    const TriangleMesh mesh = AnalyticShape::sphere(5).surfaceMesh(0.3);
    SurfaceNodes nodes = nodesFromMesh(mesh, AreaRule::Mesh);
    const SurfaceNodes before = nodes;
    sortNodesSpatially(nodes, 0.8);
    ASSERT_EQ(nodes.size(), before.size());
    auto key = [](const Vec3& p) { return std::make_tuple(p.x(), p.y(), p.z()); };
    std::vector<std::tuple<double, double, double>> a, b;
    for (size_t i = 0; i < nodes.size(); ++i) {
        a.push_back(key(before.positions[i]));
        b.push_back(key(nodes.positions[i]));
    }
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
    // Z-order visits each cell once: the nodes of one cell (one OpenVDB leaf when the cell is
    // 8 voxels) are contiguous, so a sweep over the nodes touches each leaf in one run.
    Vec3 lo = Vec3::Constant(1e300);
    for (const Vec3& p : nodes.positions) lo = lo.cwiseMin(p);
    auto cellOf = [&](const Vec3& p) {
        const Vec3 c = (p - lo) / 0.8;
        return std::make_tuple(int(c.x()), int(c.y()), int(c.z()));
    };
    std::set<std::tuple<int, int, int>> finished;
    for (size_t i = 0; i < nodes.size(); ++i) {
        const auto cell = cellOf(nodes.positions[i]);
        EXPECT_EQ(finished.count(cell), 0u) << "cell revisited at node " << i;
        if (i + 1 < nodes.size() && cellOf(nodes.positions[i + 1]) != cell) finished.insert(cell);
    }
}

TEST(SurfaceNodes, SpacingOfAStructuredGridIsItsStep)
{
    const TriangleMesh box = AnalyticShape::box(2, 2, 2).surfaceMesh(0.25);  // 8 steps per edge
    const NodeSpacing s = nodeSpacing(nodesFromMesh(box, AreaRule::Mesh));
    EXPECT_NEAR(s.min, 0.25, 1e-12);
    EXPECT_NEAR(s.max, 0.25, 1e-12);
    EXPECT_NEAR(s.mean, 0.25, 1e-12);
}

// Nodes without normals (a simulation's assets drop them) sort into the same order, and the
// normals, once dropped, take no memory.
TEST(SurfaceNodes, NodesWithoutNormalsSortAlike)
{
    SurfaceNodes whole = nodesFromMesh(AnalyticShape::sphere(5).surfaceMesh(0.3), AreaRule::Mesh);
    SurfaceNodes lean = whole;
    ASSERT_TRUE(lean.hasNormals());
    lean.dropNormals();
    EXPECT_FALSE(lean.hasNormals());
    EXPECT_EQ(lean.normals.capacity(), 0u);
    sortNodesSpatially(whole, 0.8);
    sortNodesSpatially(lean, 0.8);
    EXPECT_TRUE(lean.normals.empty());
    EXPECT_EQ(lean.positions, whole.positions);
    EXPECT_EQ(lean.areas, whole.areas);
}

// The narrow phase skips whole clusters and blocks by their bounding spheres, so every node
// must lie in exactly one block and inside its sphere, every block in exactly one cluster and
// inside its sphere; sorted nodes make the spheres small.
TEST(SurfaceNodes, BlocksCoverEveryNodeOnceInsideTheirSpheres)
{
    SurfaceNodes nodes = nodesFromMesh(AnalyticShape::sphere(5.0).surfaceMesh(0.3), AreaRule::Mesh);
    sortNodesSpatially(nodes, 0.4);
    const NodeBlocks groups = groupNodesIntoBlocks(nodes, 32, 4);
    ASSERT_TRUE(groups.matches(nodes.size()));
    int next = 0;
    double meanRadius = 0.0;
    for (const NodeBlock& b : groups.blocks) {
        EXPECT_EQ(b.begin, next);
        EXPECT_GT(b.end, b.begin);
        EXPECT_LE(b.end - b.begin, 32);
        for (int i = b.begin; i < b.end; ++i)
            EXPECT_LE((nodes.positions[i] - b.center).norm(), b.radius * (1 + 1e-12));
        next = b.end;
        meanRadius += b.radius / groups.blocks.size();
    }
    EXPECT_EQ(next, static_cast<int>(nodes.size()));
    // 32 nodes at spacing ~0.3 cover a patch of ~2.5 mm² (side ~1.6 mm); blocks are cut
    // where the box would exceed 1.5 times that, so the radius stays near 1 mm, far below R = 5.
    EXPECT_LT(meanRadius, 1.5);
    EXPECT_LT(groups.blocks.size(), nodes.size() / 10);  // and most blocks are still well filled
    next = 0;
    for (const NodeBlock& c : groups.clusters) {
        EXPECT_EQ(c.begin, next);
        EXPECT_GT(c.end, c.begin);
        EXPECT_LE(c.end - c.begin, 4);
        for (int k = c.begin; k < c.end; ++k) {
            const NodeBlock& b = groups.blocks[size_t(k)];
            EXPECT_LE((b.center - c.center).norm() + b.radius, c.radius * (1 + 1e-12));
        }
        next = c.end;
    }
    EXPECT_EQ(next, static_cast<int>(groups.blocks.size()));
    EXPECT_LT(groups.clusters.size(), groups.blocks.size() / 2);
}
