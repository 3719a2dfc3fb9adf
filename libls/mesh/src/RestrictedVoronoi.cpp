#include "lsdem/mesh/RestrictedVoronoi.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/OrderedCollect.h"
#include "lsdem/mesh/TriangleOffset.h"

#include "PointBins.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace lsdem {

namespace {

/// A seed's part of one triangle.
struct CellPiece
{
    int seed = 0;
    int triangle = 0;
    double area = 0.0;
    Vec3 moment = Vec3::Zero();
};

/// Keep the part of the convex polygon @a poly where (x − @a mid)·@a axis ≤ 0; @a scratch is
/// the caller's buffer. Returns false once nothing is left.
bool clipPolygon(std::vector<Vec3>& poly, std::vector<Vec3>& scratch, const Vec3& mid,
                 const Vec3& axis)
{
    scratch.clear();
    const size_t n = poly.size();
    bool cut = false;
    double previous = (poly[n - 1] - mid).dot(axis);
    for (size_t k = 0; k < n; ++k) {
        const Vec3& from = poly[(k + n - 1) % n];
        const Vec3& to = poly[k];
        const double here = (to - mid).dot(axis);
        if ((previous <= 0.0) != (here <= 0.0)) {
            cut = true;
            scratch.push_back(from + (previous / (previous - here)) * (to - from));
        }
        if (here <= 0.0) scratch.push_back(to);
        else cut = true;
        previous = here;
    }
    if (cut) poly.swap(scratch);
    return poly.size() >= 3;
}

/// The seeds that can own part of triangle @a t, nearest to its centroid first (by squared
/// distance, then index), into @a candidates.
void findOwnerCandidates(const TriangleMesh& mesh, int t, const std::vector<Vec3>& seeds,
                         const PointBins& grid, std::vector<std::pair<double, int>>& candidates)
{
    const auto& tri = mesh.triangles[size_t(t)];
    const Vec3 &a = mesh.vertices[size_t(tri[0])], &b = mesh.vertices[size_t(tri[1])],
               &c = mesh.vertices[size_t(tri[2])];
    const Vec3 centroid = (a + b + c) / 3.0;
    const double triangleReach = std::max({(a - centroid).norm(), (b - centroid).norm(),
                                           (c - centroid).norm()});
    // A point x of the triangle is owned by a seed no farther than the centroid's nearest
    // seed s0 is from x: |x − s0| ≤ d0 + triangleReach. So an owner is within
    // d0 + 2·triangleReach of the centroid, and no seed farther can own anything here.
    const double radius = grid.nearestDistance(centroid) + 2.0 * triangleReach;
    candidates.clear();
    grid.forEachWithin(centroid, radius * (1.0 + 1e-12), [&](int s) {
        candidates.emplace_back((seeds[size_t(s)] - centroid).squaredNorm(), s);
    });
    std::sort(candidates.begin(), candidates.end());
}

/// The pieces of triangle @a t owned by each seed that owns any of it, @a candidates its
/// findOwnerCandidates.
void clipTriangle(const TriangleMesh& mesh, int t, const std::vector<Vec3>& seeds,
                  const std::vector<std::pair<double, int>>& candidates, std::vector<Vec3>& poly,
                  std::vector<Vec3>& scratch, std::vector<CellPiece>& out)
{
    const auto& tri = mesh.triangles[size_t(t)];
    const Vec3 &a = mesh.vertices[size_t(tri[0])], &b = mesh.vertices[size_t(tri[1])],
               &c = mesh.vertices[size_t(tri[2])];
    const Vec3 cross = (b - a).cross(c - a);
    const double twiceArea = cross.norm();
    if (!(twiceArea > 0.0)) return;
    const Vec3 normal = cross / twiceArea;
    for (const auto& [unused, i] : candidates) {
        const Vec3& pi = seeds[size_t(i)];
        poly.assign({a, b, c});
        // How far the polygon left reaches from the seed, squared.
        double reach2 = std::max({(a - pi).squaredNorm(), (b - pi).squaredNorm(),
                                  (c - pi).squaredNorm()});
        bool left = true;
        for (const auto& [unused2, j] : candidates) {
            if (j == i) continue;
            const Vec3 axis = seeds[size_t(j)] - pi;
            const double gap2 = axis.squaredNorm();
            if (gap2 == 0.0) {
                // Two seeds at one point: the first in index order owns what they share.
                if (j < i) { left = false; break; }
                continue;
            }
            if (gap2 > 4.0 * reach2) continue;  // the bisector is beyond every vertex
            if (!clipPolygon(poly, scratch, 0.5 * (pi + seeds[size_t(j)]), axis)) {
                left = false;
                break;
            }
            reach2 = 0.0;
            for (const Vec3& v : poly) reach2 = std::max(reach2, (v - pi).squaredNorm());
        }
        if (!left) continue;
        CellPiece piece;
        piece.seed = i;
        piece.triangle = t;
        for (size_t k = 1; k + 1 < poly.size(); ++k) {
            const double part = 0.5 * (poly[k] - poly[0]).cross(poly[k + 1] - poly[0]).dot(normal);
            piece.area += part;
            piece.moment += part * (poly[0] + poly[k] + poly[k + 1]) / 3.0;
        }
        if (piece.area > 0.0) out.push_back(piece);
    }
}

/// @a mesh with each triangle larger than @a largest split into n² equal ones in its own
/// plane (corners not shared: the cells need no connectivity). A triangle holding many seeds
/// costs the square of their number to clip; its parts cost a few each.
TriangleMesh splitLargeTriangles(const TriangleMesh& mesh, double largest)
{
    TriangleMesh split;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3 &a = mesh.vertices[size_t(tri[0])], &b = mesh.vertices[size_t(tri[1])],
                   &c = mesh.vertices[size_t(tri[2])];
        const int n = std::max(1, int(std::ceil(std::sqrt(triangleArea(mesh, int(t)) / largest))));
        const int first = int(split.vertices.size());
        // Vertex (i, j) = a + (i/n)(b − a) + (j/n)(c − a), i + j ≤ n, row by row in i.
        std::vector<int> rowStart(size_t(n) + 2, first);
        for (int i = 0; i <= n; ++i) {
            rowStart[size_t(i)] = int(split.vertices.size());
            for (int j = 0; i + j <= n; ++j)
                split.vertices.push_back(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a));
        }
        auto at = [&](int i, int j) { return rowStart[size_t(i)] + j; };
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                split.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
                if (i + j + 1 < n) split.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
    }
    return split;
}

} // namespace

std::vector<RestrictedVoronoiCell> restrictedVoronoiCells(const TriangleMesh& input,
                                                          const std::vector<Vec3>& seeds,
                                                          CellSides sides)
{
    if (seeds.empty()) throw Error("", "restricted Voronoi cells need at least one seed");
    // Triangles larger than two cells are split first (their pieces are the same polygons).
    const double cellArea = surfaceArea(input) / double(seeds.size());
    TriangleMesh refined;
    bool large = false;
    for (int t = 0; t < int(input.triangles.size()) && !large; ++t)
        large = triangleArea(input, t) > 2.0 * cellArea;
    if (large) refined = splitLargeTriangles(input, 2.0 * cellArea);
    const TriangleMesh& mesh = large ? refined : input;
    const auto bounds = meshBounds(mesh);
    // Cells about the seeds' spacing: a few seeds in each.
    const double area = std::max(surfaceArea(mesh), std::numeric_limits<double>::min());
    const PointBins grid(seeds, bounds[0], bounds[1], 1.5 * std::sqrt(area / double(seeds.size())));
    std::vector<RestrictedVoronoiCell> cells(seeds.size());
    auto normalOf = [&mesh](int t) {
        const auto& tri = mesh.triangles[size_t(t)];
        const Vec3& a = mesh.vertices[size_t(tri[0])];
        return Vec3((mesh.vertices[size_t(tri[1])] - a)
                        .cross(mesh.vertices[size_t(tri[2])] - a)
                        .normalized());
    };
    // Each seed's own side of the surface: the normal of its cell's triangle nearest to it
    // (the one it lies on, for a seed on the surface).
    std::vector<double> homeDistance(seeds.size(), std::numeric_limits<double>::infinity());
    std::vector<Vec3> homeNormal(seeds.size(), Vec3::Zero());
    // Chunks of a fixed share of the triangles (not of the threads): the same pieces in the
    // same order on any thread count, and a coarse mesh holding many seeds still split. The
    // pieces are summed a few chunks at a time, in triangle order (the same sums on any
    // thread count), so only those chunks' pieces are held at once.
    const size_t chunk = std::clamp<size_t>(mesh.triangles.size() / 64, 16, 2048);
    constexpr size_t kChunksAtATime = 8;
    // The pieces of each triangle that @a clips(t, its candidate owners) asks for, handed to
    // @a consume in triangle order.
    auto forEachPiece = [&](auto&& clips, auto&& consume) {
        consumeInOrder<CellPiece>(
            mesh.triangles.size(), chunk, kChunksAtATime,
            [&](size_t begin, size_t end, std::vector<CellPiece>& out) {
                std::vector<std::pair<double, int>> candidates;
                std::vector<Vec3> poly, scratch;
                for (size_t t = begin; t < end; ++t) {
                    findOwnerCandidates(mesh, int(t), seeds, grid, candidates);
                    if (clips(int(t), candidates))
                        clipTriangle(mesh, int(t), seeds, candidates, poly, scratch, out);
                }
            },
            consume);
    };
    forEachPiece(
        [](int, const auto&) { return true; },
        [&](const CellPiece& piece) {
            const size_t s = size_t(piece.seed);
            const Vec3 normal = normalOf(piece.triangle);
            cells[s].area += piece.area;
            cells[s].moment += piece.moment;
            cells[s].normalArea += piece.area * normal;
            const double distance =
                offsetFromTriangle(seeds[s], mesh, piece.triangle).squaredNorm();
            if (distance < homeDistance[s]) {
                homeDistance[s] = distance;
                homeNormal[s] = normal;
            }
        });
    if (sides == CellSides::Skipped) return cells;

    // The second pass, once each seed's own normal is known: the pieces on triangles turned
    // by more than 120° from it, the other side of a thin part (a scan's noise tilts
    // neighbouring facets by tens of degrees). Made again rather than kept from the first
    // (16 bytes a piece, about two a triangle: the largest item of a node layout's peak), and
    // only on triangles that some candidate owner faces away from.
    auto facesAway = [&](int triangle, int seed) {
        return normalOf(triangle).dot(homeNormal[size_t(seed)]) < -0.5;
    };
    forEachPiece(
        [&](int t, const std::vector<std::pair<double, int>>& candidates) {
            return std::any_of(candidates.begin(), candidates.end(),
                               [&](const auto& c) { return facesAway(t, c.second); });
        },
        [&](const CellPiece& piece) {
            if (facesAway(piece.triangle, piece.seed))
                cells[size_t(piece.seed)].facingAway += piece.area;
        });
    return cells;
}

} // namespace lsdem
