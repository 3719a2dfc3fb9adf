#include "lsdem/mesh/CentroidalNodes.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/PortableRandom.h"
#include "lsdem/core/ReleaseMemory.h"
#include "lsdem/mesh/ClosestPointGrid.h"
#include "lsdem/mesh/SampleElimination.h"

#include "VertexTriangles.h"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace lsdem {

namespace {

/// Uniform in [0, 1) from draw @a k of the stream @a base: SplitMix64 of a counter, a
/// counter-based generator (no state to seed, and draw k needs no draw before it).
double uniformDraw(uint64_t base, uint64_t k)
{
    return double(splitMix64(base + k) >> 11) * 0x1.0p-53;
}

/// About @a perArea random points per unit area, uniform over each triangle; triangle t's
/// points come from its own stream, so they do not depend on any other triangle.
std::vector<Vec3> randomSurfacePoints(const TriangleMesh& mesh, double perArea, uint64_t seed)
{
    // Triangle t's stream and its count: the expected number, one more with the chance of
    // its fraction (draw 0). Counted first, so the points are stored without regrowing.
    auto streamOf = [&](size_t t) { return splitMix64(splitMix64(seed) ^ splitMix64(t + 1)); };
    auto countOf = [&](size_t t, uint64_t base) {
        const double expected = triangleArea(mesh, int(t)) * perArea;
        return int(expected) + (uniformDraw(base, 0) < expected - std::floor(expected));
    };
    size_t total = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) total += size_t(countOf(t, streamOf(t)));
    std::vector<Vec3> points;
    points.reserve(total);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const uint64_t base = streamOf(t);
        const int count = countOf(t, base);
        const auto& tri = mesh.triangles[t];
        const Vec3 &a = mesh.vertices[size_t(tri[0])], &b = mesh.vertices[size_t(tri[1])],
                   &c = mesh.vertices[size_t(tri[2])];
        for (int k = 0; k < count; ++k) {
            // Uniform over the triangle: the square root spreads the first draw by area.
            const double r1 = std::sqrt(uniformDraw(base, 2 * uint64_t(k) + 1));
            const double r2 = uniformDraw(base, 2 * uint64_t(k) + 2);
            points.push_back((1.0 - r1) * a + r1 * (1.0 - r2) * b + r1 * r2 * c);
        }
    }
    return points;
}

} // namespace

CentroidalNodes placeCentroidalNodes(const TriangleMesh& mesh, size_t count,
                                     const CentroidalNodeOptions& options)
{
    if (count < 4) throw Error("", "node placement needs at least 4 nodes");
    const double area = surfaceArea(mesh);
    if (!(area > 0.0 && std::isfinite(area)))
        throw Error("", "node placement: the mesh has no area");

    // Candidates: a few times the nodes wanted (never fewer than the count), then thinned.
    const double wanted = double(count) * std::max(options.candidatesPerNode, 2);
    std::vector<Vec3> candidates = randomSurfacePoints(mesh, wanted / area, options.seed);
    for (uint64_t extra = 1; candidates.size() < count; ++extra) {
        const std::vector<Vec3> more = randomSurfacePoints(mesh, wanted / area, options.seed + extra);
        candidates.insert(candidates.end(), more.begin(), more.end());
    }
    CentroidalNodes nodes;
    nodes.positions.reserve(count);
    for (int i : eliminateSamples(candidates, count, area))
        nodes.positions.push_back(candidates[size_t(i)]);
    std::vector<Vec3>().swap(candidates);
    // The elimination's lists are the stage's largest blocks; Lloyd's steps allocate on the
    // pool's threads, which could not reuse them where malloc kept them.
    releaseFreedMemory();

    // Lloyd: each node to its cell's centroid, put back on the surface (the centroid of a
    // curved cell lies slightly inside).
    const ClosestPointGrid surface(mesh, std::sqrt(area / double(count)));
    for (int iteration = 0; iteration < options.lloydIterations; ++iteration) {
        const std::vector<RestrictedVoronoiCell> cells =
            restrictedVoronoiCells(mesh, nodes.positions, CellSides::Skipped);
        tbb::parallel_for(size_t(0), count, [&](size_t i) {
            if (cells[i].area > 0.0)
                nodes.positions[i] = surface.closestPoint(cells[i].moment / cells[i].area);
        });
    }
    nodes.cells = restrictedVoronoiCells(mesh, nodes.positions);
    return nodes;
}

SharpEdges countSharpEdges(const TriangleMesh& mesh, double angleDeg)
{
    const VertexTriangles aroundVertex(mesh);
    auto normalOf = [&mesh](int t) {
        const auto& tri = mesh.triangles[size_t(t)];
        const Vec3& a = mesh.vertices[size_t(tri[0])];
        return Vec3((mesh.vertices[size_t(tri[1])] - a).cross(mesh.vertices[size_t(tri[2])] - a));
    };
    const double cosAngle = std::cos(angleDeg * kPi / 180.0);
    SharpEdges sharp;
    std::vector<int> sharpAtVertex(mesh.vertices.size(), 0);
    std::vector<int> users;
    for (int t = 0; t < int(mesh.triangles.size()); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto& tri = mesh.triangles[size_t(t)];
            const int a = tri[k], b = tri[(k + 1) % 3];
            // (A triangle with a repeated corner has one edge twice: it is looked at once.)
            auto samePair = [&](int j) {
                return std::minmax(tri[j], tri[(j + 1) % 3]) == std::minmax(a, b);
            };
            if (a == b || (k > 0 && samePair(0)) || (k > 1 && samePair(1))) continue;
            users.clear();
            aroundVertex.forEachUsingEdge(a, b, [&](int u) { users.push_back(u); });
            if (users.front() != t) continue;  // each edge once, at its first triangle
            // Its users in increasing order, two by two (a closed mesh's edge has two).
            for (size_t i = 0; i + 1 < users.size(); ++i) {
                const Vec3 n1 = normalOf(users[i]), n2 = normalOf(users[i + 1]);
                const double norms = n1.norm() * n2.norm();
                if (!(norms > 0.0 && n1.dot(n2) < cosAngle * norms)) continue;
                ++sharp.edges;
                ++sharpAtVertex[size_t(a)];
                ++sharpAtVertex[size_t(b)];
            }
        }
    sharp.looseEnds = size_t(std::count(sharpAtVertex.begin(), sharpAtVertex.end(), 1));
    return sharp;
}

bool sharpEdgesLookLikeNoise(const SharpEdges& s)
{
    // Lines of sharp edges (a shape's) have loose ends only where a crease fades out.
    constexpr size_t kSharpEdgesPerLooseEnd = 20;
    if (s.edges == 0) return false;
    if (s.looseEnds == 2 * s.edges) return true;
    return s.edges >= kManySharpEdges && s.looseEnds * kSharpEdgesPerLooseEnd >= s.edges;
}

} // namespace lsdem
