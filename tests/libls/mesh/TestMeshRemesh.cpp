// Tests of remeshIsotropic and edgeLengthForNodeCount: edge lengths, closedness, staying on
// the input surface, keeping sharp edges, and the node count a chosen edge length gives.
#include "lsdem/core/Error.h"
#include "lsdem/mesh/MeshRemesh.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

using lsdem::RemeshOptions;
using lsdem::TriangleMesh;
using lsdem::Vec3;

namespace {

using lsdem::test::makeBox;
using lsdem::test::makeIcosphere;
using lsdem::test::signedVolume;

/// Undirected edges, each once.
std::set<std::pair<int, int>> undirectedEdges(const TriangleMesh& mesh)
{
    std::set<std::pair<int, int>> edges;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    return edges;
}

double meanEdgeLength(const TriangleMesh& mesh)
{
    const auto edges = undirectedEdges(mesh);
    double sum = 0.0;
    for (const auto& e : edges) sum += (mesh.vertices[e.first] - mesh.vertices[e.second]).norm();
    return sum / static_cast<double>(edges.size());
}

/// Closed, manifold and consistently oriented: every directed edge occurs once, and so does
/// its reverse. Also every vertex is used and every index is in range.
::testing::AssertionResult isClosedOriented(const TriangleMesh& mesh)
{
    std::map<std::pair<int, int>, int> directed;
    std::vector<bool> used(mesh.vertices.size());
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            if (t[k] < 0 || t[k] >= static_cast<int>(mesh.vertices.size()))
                return ::testing::AssertionFailure() << "index " << t[k] << " out of range";
            used[t[k]] = true;
            ++directed[{t[k], t[(k + 1) % 3]}];
        }
    for (const auto& [edge, count] : directed) {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1)
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " is not closed/oriented";
    }
    if (std::find(used.begin(), used.end(), false) != used.end())
        return ::testing::AssertionFailure() << "unused vertex";
    return ::testing::AssertionSuccess();
}

/// Euler characteristic V - E + F; 2 for a closed surface of genus 0.
long eulerCharacteristic(const TriangleMesh& mesh)
{
    return static_cast<long>(mesh.vertices.size()) -
           static_cast<long>(undirectedEdges(mesh).size()) +
           static_cast<long>(mesh.triangles.size());
}

TriangleMesh remeshed(const TriangleMesh& mesh, double target)
{
    RemeshOptions options;
    options.targetEdgeLength = target;
    return lsdem::remeshIsotropic(mesh, options);
}

TEST(MeshRemesh, SphereGetsTheTargetEdgeLengthAndStaysOnTheInputSurface)
{
    const TriangleMesh input = makeIcosphere(3);  // 642 vertices, edges 0.14 to 0.16
    const TriangleMesh out = remeshed(input, 0.1);

    EXPECT_TRUE(isClosedOriented(out));
    EXPECT_EQ(eulerCharacteristic(out), 2);
    // The target is the wanted mean edge length (measured: within 1%).
    EXPECT_NEAR(meanEdgeLength(out), 0.1, 0.1 * 0.1);

    // The remesher projects vertices onto the input polyhedron, not onto the sphere. The
    // input lies between the spheres of radius 1 (its vertices; it is convex) and rMin (its
    // closest face plane), so every output vertex must too.
    double rMin = 1.0;
    for (const auto& t : input.triangles) {
        const Vec3& a = input.vertices[t[0]];
        const Vec3 n = (input.vertices[t[1]] - a).cross(input.vertices[t[2]] - a).normalized();
        rMin = std::min(rMin, std::abs(n.dot(a)));
    }
    ASSERT_GT(rMin, 0.99);  // the input itself is within 0.01 of the unit sphere
    for (const Vec3& v : out.vertices) {
        EXPECT_LE(v.norm(), 1.0 + 1e-12);
        EXPECT_GE(v.norm(), rMin - 1e-12);
    }
    // Inscribed in the convex input, so the volume can only shrink: by about 0.4 h^2 for
    // chords of length h on a unit sphere (the input, edges 0.15, has 0.86% less than the
    // ball), i.e. 0.4% at h = 0.1; 1% leaves room for the spread of edge lengths.
    const double inputVolume = signedVolume(input);
    EXPECT_LT(signedVolume(out), inputVolume);
    EXPECT_GT(signedVolume(out), inputVolume * (1 - 0.01));
}

TEST(MeshRemesh, BoxKeepsItsSharpEdgesAndCorners)
{
    const Vec3 lo(0, 0, 0), hi(1, 2, 3);
    const TriangleMesh out = remeshed(makeBox(lo, hi), 0.2);

    EXPECT_TRUE(isClosedOriented(out));
    EXPECT_EQ(eulerCharacteristic(out), 2);
    // Sharp edges kept means the result is exactly the box again.
    EXPECT_NEAR(signedVolume(out), 6.0, 6.0 * 1e-9);
    EXPECT_NEAR(lsdem::surfaceArea(out), 22.0, 22.0 * 1e-9);
    EXPECT_NEAR(meanEdgeLength(out), 0.2, 0.2 * 0.1);  // measured: within 1%
    // Near-equilateral triangles: about 22 / (sqrt(3) / 2 * 0.2^2) = 635 vertices.
    EXPECT_NEAR(static_cast<double>(out.vertices.size()), 635.0, 0.15 * 635.0);

    // The faces of the box (0..5: -x, +x, -y, +y, -z, +z) a point lies on.
    auto facesOf = [&](const Vec3& p) {
        std::set<int> faces;
        for (int axis = 0; axis < 3; ++axis) {
            if (std::abs(p[axis] - lo[axis]) < 1e-12) faces.insert(2 * axis);
            if (std::abs(p[axis] - hi[axis]) < 1e-12) faces.insert(2 * axis + 1);
        }
        return faces;
    };
    int corners = 0;
    for (const Vec3& v : out.vertices) {
        EXPECT_TRUE(((v.array() >= lo.array() - 1e-12) && (v.array() <= hi.array() + 1e-12))
                        .all());
        const auto faces = facesOf(v);
        EXPECT_FALSE(faces.empty()) << "vertex off the box surface: " << v.transpose();
        if (faces.size() == 3) ++corners;
    }
    EXPECT_EQ(corners, 8);
    // No triangle cuts across an edge of the box: all its corners lie on one common face.
    for (const auto& t : out.triangles) {
        std::set<int> common = facesOf(out.vertices[t[0]]);
        for (int k = 1; k < 3; ++k) {
            const auto faces = facesOf(out.vertices[t[k]]);
            std::set<int> both;
            std::set_intersection(common.begin(), common.end(), faces.begin(), faces.end(),
                                  std::inserter(both, both.begin()));
            common = both;
        }
        EXPECT_FALSE(common.empty()) << "triangle across a box edge";
    }
    // The box edges (total length 24) are resolved at about the target spacing too: count
    // the mesh edges lying on them (both ends on the same two faces).
    int onBoxEdges = 0;
    for (const auto& [a, b] : undirectedEdges(out)) {
        std::set<int> both;
        const auto fa = facesOf(out.vertices[a]), fb = facesOf(out.vertices[b]);
        std::set_intersection(fa.begin(), fa.end(), fb.begin(), fb.end(),
                              std::inserter(both, both.begin()));
        if (both.size() >= 2) ++onBoxEdges;
    }
    EXPECT_NEAR(onBoxEdges, 24 / 0.2, 0.2 * 24 / 0.2);
}

TEST(MeshRemesh, NodeCountFollowsTheChosenEdgeLengthWhateverTheInput)
{
    // Inputs coarser than, about as fine as (edges 0.069 to 0.083 against h = 0.085), and
    // much finer than the target. CGAL alone gives 20 to 35% more nodes, and from the middle
    // one it hardly changes the mesh; measured here: within 3%.
    for (const int level : {2, 4, 6}) {
        const TriangleMesh input = makeIcosphere(level);
        const double area = lsdem::surfaceArea(input);
        const double h = lsdem::edgeLengthForNodeCount(area, 2000);
        const TriangleMesh out = remeshed(input, h);
        EXPECT_TRUE(isClosedOriented(out)) << "level " << level;
        EXPECT_NEAR(static_cast<double>(out.vertices.size()), 2000.0, 0.15 * 2000.0)
            << "level " << level;
    }
}

TEST(MeshRemesh, EdgeLengthForNodeCountInvertsTheEquilateralArea)
{
    // 2 n equilateral triangles of side h cover n sqrt(3) / 2 h^2.
    for (const double h : {1e-3, 0.05, 2.0})
        for (const int n : {1, 100, 123456}) {
            const double area = n * std::sqrt(3.0) / 2.0 * h * h;
            EXPECT_NEAR(lsdem::edgeLengthForNodeCount(area, n), h, 1e-14 * h);
        }
    EXPECT_THROW(lsdem::edgeLengthForNodeCount(1.0, 0), lsdem::Error);
    EXPECT_THROW(lsdem::edgeLengthForNodeCount(1.0, -5), lsdem::Error);
    EXPECT_THROW(lsdem::edgeLengthForNodeCount(0.0, 10), lsdem::Error);
    EXPECT_THROW(lsdem::edgeLengthForNodeCount(-1.0, 10), lsdem::Error);
    EXPECT_THROW(lsdem::edgeLengthForNodeCount(std::nan(""), 10), lsdem::Error);
}

TEST(MeshRemesh, RefusesBadTargetEdgeLengths)
{
    const TriangleMesh box = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    for (const double target : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity()})
        EXPECT_THROW(remeshed(box, target), lsdem::Error) << target;
}

TEST(MeshRemesh, RefusesOpenOrEmptyMeshes)
{
    TriangleMesh open = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    open.triangles.pop_back();
    EXPECT_THROW(remeshed(open, 0.2), lsdem::Error);
    EXPECT_THROW(remeshed(TriangleMesh{}, 0.2), lsdem::Error);
    // Two triangles running the same way along an edge cannot be stitched together.
    TriangleMesh twisted = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
    std::swap(twisted.triangles[0][1], twisted.triangles[0][2]);
    EXPECT_THROW(remeshed(twisted, 0.2), lsdem::Error);
}

} // namespace

TEST(MeshRemesh, FineInputKeptAsItIsGetsTheTargetEdgeLengthToo)
{
    // An input already finer than 0.77 of the target (edges ~0.08 against 0.15) is remeshed
    // without the refinement to 0.44 of the target when asked (keepFineInput): the result is
    // still a closed sphere-like surface on the input, with the target mean edge within 5 %
    // (measured 1 to 3.5 % on the bumpy pebbles of bench_libls) and a node count within 8 %
    // of the refined path's (measured 4 % on the 100k-triangle pebble).
    const TriangleMesh input = makeIcosphere(4);  // 2562 vertices, edges 0.07 to 0.08
    RemeshOptions options;
    options.targetEdgeLength = 0.15;
    const TriangleMesh refined = lsdem::remeshIsotropic(input, options);
    options.keepFineInput = true;
    const TriangleMesh kept = lsdem::remeshIsotropic(input, options);

    EXPECT_TRUE(isClosedOriented(kept));
    EXPECT_EQ(eulerCharacteristic(kept), 2);
    EXPECT_NEAR(meanEdgeLength(kept), 0.15, 0.05 * 0.15);
    for (const Vec3& v : kept.vertices) EXPECT_LE(v.norm(), 1.0 + 1e-12);
    const double ratio = double(kept.vertices.size()) / double(refined.vertices.size());
    EXPECT_NEAR(ratio, 1.0, 0.08);
}
