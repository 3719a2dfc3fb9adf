#include "lsdem/mesh/MeshValidation.h"

#include "MeshPartCrossing.h"
#include "VertexTriangles.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

namespace lsdem {

namespace {

/// A triangle across an edge, and whether both run along that edge the same way.
struct Neighbour
{
    int triangle = -1;  ///< -1: none (an edge used once, or by three or more)
    bool sameDirection = false;
};

/// A triangle's neighbours across its edges, in a fixed three slots (a vector each held about
/// three times their size in a 100k-triangle mesh's validation, its peak).
using Neighbours = std::array<Neighbour, 3>;

/// The triangles of one connected component and its bounding box.
struct Component
{
    std::vector<int> triangles;
    Vec3 lo, hi;
    double volume = 0.0;
};

/// "1 edge", "3 edges".
std::string countOf(int n, const std::string& noun)
{
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

void checkIndicesAndCoordinates(const TriangleMesh& mesh, const std::string& source)
{
    if (mesh.empty())
        throw Error(source, "the mesh has no triangles", "export the surface of the solid");
    const int vertexCount = static_cast<int>(mesh.vertices.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int v : mesh.triangles[t])
            if (v < 0 || v >= vertexCount)
                throw Error(source,
                            "triangle " + std::to_string(t) + " refers to vertex " +
                                std::to_string(v) + ", but there are only " +
                                std::to_string(vertexCount) + " vertices",
                            "export the mesh again");
    // Unused vertices are checked too: bounds and sampling look at every vertex.
    for (int v = 0; v < vertexCount; ++v)
        for (int axis = 0; axis < 3; ++axis)
            if (!std::isfinite(mesh.vertices[v][axis]))
                throw Error(source,
                            "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                                numberText(mesh.vertices[v][axis]) + ")",
                            "fix or remove that vertex in the mesh and export it again");
}

/// Drop triangles that repeat a vertex or whose area is negligible next to the mean.
int removeDegenerateTriangles(TriangleMesh& mesh, const std::string& source)
{
    const int count = static_cast<int>(mesh.triangles.size());
    std::vector<double> areas(count);
    double total = 0.0;
    for (int t = 0; t < count; ++t) total += areas[t] = triangleArea(mesh, t);
    if (!(total > 0.0))
        throw Error(source, "all triangles have zero area", "export the surface of the solid");
    const double minArea = 1e-12 * total / count;

    std::vector<std::array<int, 3>> kept;
    kept.reserve(count);
    for (int t = 0; t < count; ++t) {
        const auto& tri = mesh.triangles[t];
        const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
        if (!repeated && areas[t] >= minArea) kept.push_back(tri);
    }
    const int removed = count - static_cast<int>(kept.size());
    mesh.triangles = std::move(kept);
    return removed;
}

/// Refuse open or non-manifold surfaces; otherwise return each triangle's three neighbours.
std::vector<Neighbours> findNeighbours(const TriangleMesh& mesh, const std::string& source,
                                       int removedDegenerate)
{
    const VertexTriangles aroundVertex(mesh);
    std::vector<Neighbours> neighbours(mesh.triangles.size());
    int boundaryEdges = 0, nonManifoldEdges = 0;
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
        const auto& tri = mesh.triangles[size_t(t)];
        // Each edge's users, in increasing order; the edge is counted by its first.
        std::array<std::uint64_t, 3> keys{};
        int found = 0;
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k], b = tri[(k + 1) % 3];
            int users = 0, first = -1, other = -1;
            aroundVertex.forEachUsingEdge(a, b, [&](int u) {
                if (users++ == 0) first = u;
                if (u != t) other = u;
            });
            if (first == t) {
                if (users == 1) ++boundaryEdges;
                if (users >= 3) ++nonManifoldEdges;
            }
            if (users != 2) continue;
            // The two run the same way when the other also goes a → b.
            const auto& o = mesh.triangles[size_t(other)];
            bool same = false;
            for (int j = 0; j < 3; ++j) same |= o[j] == a && o[(j + 1) % 3] == b;
            const auto lo = std::uint32_t(std::min(a, b)), hi = std::uint32_t(std::max(a, b));
            keys[size_t(found)] = (std::uint64_t(lo) << 32) | hi;
            neighbours[size_t(t)][size_t(found++)] = {other, same};
        }
        // In the order of their edges' (lower, higher) vertex pairs, as a sorted list of every
        // edge would give them (the orientation's walk, and so its result, follows this order).
        for (int i = 1; i < found; ++i)
            for (int j = i; j > 0 && keys[size_t(j)] < keys[size_t(j - 1)]; --j) {
                std::swap(keys[size_t(j)], keys[size_t(j - 1)]);
                std::swap(neighbours[size_t(t)][size_t(j)], neighbours[size_t(t)][size_t(j - 1)]);
            }
    }

    if (boundaryEdges > 0) {
        std::string problem = "open surface: " + countOf(boundaryEdges, "boundary edge") +
                              " (the mesh is not watertight)";
        if (nonManifoldEdges > 0)
            problem += ", and " + countOf(nonManifoldEdges, "non-manifold edge");
        if (removedDegenerate > 0)
            problem += ", after dropping " + countOf(removedDegenerate, "degenerate triangle");
        throw Error(source, problem,
                    "close the holes (e.g. MeshLab 'Close Holes' / Blender 'Fill Holes') and "
                    "bake again");
    }
    if (nonManifoldEdges > 0)
        throw Error(source,
                    "non-manifold surface: " + countOf(nonManifoldEdges, "edge") +
                        " shared by three or more triangles",
                    "separate parts that touch along an edge and remove duplicate faces (e.g. "
                    "MeshLab 'Repair non Manifold Edges'), then bake again");
    return neighbours;
}

void flipTriangle(std::array<int, 3>& tri) { std::swap(tri[1], tri[2]); }

/// Make the orientation consistent inside each connected component, flipping the fewer
/// triangles; returns the components and adds the flips to @a reoriented.
std::vector<Component> orientComponents(TriangleMesh& mesh,
                                        const std::vector<Neighbours>& neighbours,
                                        const std::string& source, int& reoriented)
{
    const int count = static_cast<int>(mesh.triangles.size());
    std::vector<signed char> flip(count, -1);  // -1: not reached yet
    std::vector<Component> components;
    for (int seed = 0; seed < count; ++seed) {
        if (flip[seed] >= 0) continue;
        Component comp;
        flip[seed] = 0;
        comp.triangles.push_back(seed);
        // The member list doubles as the breadth-first queue.
        for (std::size_t next = 0; next < comp.triangles.size(); ++next) {
            const int t = comp.triangles[next];
            for (const Neighbour& n : neighbours[t]) {
                if (n.triangle < 0) break;  // (the slots in use come first)
                // Neighbours agree when they run along their shared edge in opposite ways.
                const signed char wanted = flip[t] ^ static_cast<signed char>(n.sameDirection);
                if (flip[n.triangle] < 0) {
                    flip[n.triangle] = wanted;
                    comp.triangles.push_back(n.triangle);
                } else if (flip[n.triangle] != wanted) {
                    throw Error(source,
                                "the surface cannot be oriented consistently (it is one-sided, "
                                "like a Klein bottle)",
                                "rebuild the surface of the solid (e.g. remesh it in MeshLab "
                                "or Blender) and bake again");
                }
            }
        }
        const auto flipped = static_cast<std::size_t>(
            std::count_if(comp.triangles.begin(), comp.triangles.end(),
                          [&](int t) { return flip[t] == 1; }));
        // The seed may be the odd one out: flipping the complement is equally consistent.
        const bool invert = 2 * flipped > comp.triangles.size();
        for (int t : comp.triangles)
            if ((flip[t] == 1) != invert) flipTriangle(mesh.triangles[t]);
        reoriented += static_cast<int>(invert ? comp.triangles.size() - flipped : flipped);
        components.push_back(std::move(comp));
    }
    return components;
}

/// Signed volume and bounds of each component, relative to @a origin to limit cancellation.
void measureComponents(const TriangleMesh& mesh, const Vec3& origin,
                       std::vector<Component>& components)
{
    for (Component& comp : components) {
        comp.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
        comp.hi = -comp.lo;
        double sixTimesVolume = 0.0;
        for (int t : comp.triangles) {
            const auto& tri = mesh.triangles[t];
            const Vec3 a = mesh.vertices[tri[0]] - origin;
            const Vec3 b = mesh.vertices[tri[1]] - origin;
            const Vec3 c = mesh.vertices[tri[2]] - origin;
            sixTimesVolume += a.dot(b.cross(c));
            for (int v : tri) {
                comp.lo = comp.lo.cwiseMin(mesh.vertices[v]);
                comp.hi = comp.hi.cwiseMax(mesh.vertices[v]);
            }
        }
        comp.volume = sixTimesVolume / 6.0;
    }
}

/// How many times the closed surface @a comp winds around @a p (solid angle / 4 kPi).
double windingNumber(const TriangleMesh& mesh, const Component& comp, const Vec3& p)
{
    double solidAngle = 0.0;
    for (int t : comp.triangles) {
        const auto& tri = mesh.triangles[t];
        const Vec3 a = mesh.vertices[tri[0]] - p;
        const Vec3 b = mesh.vertices[tri[1]] - p;
        const Vec3 c = mesh.vertices[tri[2]] - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        // Van Oosterom & Strackee: the solid angle of a triangle seen from the origin.
        solidAngle += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc +
                                                              b.dot(c) * la + c.dot(a) * lb);
    }
    return solidAngle / (4.0 * kPi);
}

/// Whether component @a inner lies inside the closed surface @a outer.
bool isInside(const TriangleMesh& mesh, const Component& inner, const Component& outer)
{
    const bool boxInside = (outer.lo.array() < inner.lo.array()).all() &&
                           (inner.hi.array() < outer.hi.array()).all();
    if (!boxInside) return false;
    const Vec3& probe = mesh.vertices[mesh.triangles[inner.triangles.front()][0]];
    return std::abs(windingNumber(mesh, outer, probe)) > 0.5;
}

/// Refuse parts whose surfaces cross or touch (checked before nesting, which assumes none do).
void checkPartsApart(const TriangleMesh& mesh, const std::vector<Component>& components,
                     const std::string& source)
{
    if (components.size() < 2) return;
    std::vector<MeshPart> parts;
    for (const Component& comp : components) parts.push_back({&comp.triangles, comp.lo, comp.hi});
    const std::optional<PartCrossing> crossing = findPartCrossing(mesh, parts);
    if (!crossing) return;
    const auto& tri = mesh.triangles[static_cast<size_t>(crossing->triangleA)];
    const Vec3 near = (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.0;
    throw Error(source,
                "two parts of the surface (" +
                    countOf(static_cast<int>(components[crossing->partA].triangles.size()),
                            "triangle") +
                    " and " +
                    countOf(static_cast<int>(components[crossing->partB].triangles.size()),
                            "triangle") +
                    ") cross or touch each other near (" + numberText(near.x()) + ", " +
                    numberText(near.y()) + ", " + numberText(near.z()) +
                    "): their overlap would count twice in the mass and leave a false surface "
                    "inside the grain",
                "merge overlapping parts into one closed surface (a boolean union, e.g. in "
                "Blender, MeshLab or OpenSCAD) and bake again");
}

/// Turn inside-out components around. A component nested in another (a cavity, or a part
/// inside a cavity) keeps its orientation relative to its outermost container, so a hollow
/// solid stays hollow; the others must enclose positive volume on their own.
bool orientOutward(TriangleMesh& mesh, std::vector<Component>& components)
{
    const int count = static_cast<int>(components.size());
    std::vector<int> outermost(count);
    for (int i = 0; i < count; ++i) {
        outermost[i] = i;
        if (count == 1) break;
        std::vector<int> containers;
        for (int j = 0; j < count; ++j)
            if (j != i && isInside(mesh, components[i], components[j])) containers.push_back(j);
        // Nested shells form a chain: the outermost container has the largest box.
        for (int j : containers)
            if (outermost[i] == i ||
                (components[j].hi - components[j].lo).prod() >
                    (components[outermost[i]].hi - components[outermost[i]].lo).prod())
                outermost[i] = j;
    }
    std::vector<bool> reverse(count);
    for (int i = 0; i < count; ++i) reverse[i] = components[outermost[i]].volume < 0.0;
    bool any = false;
    for (int i = 0; i < count; ++i) {
        if (!reverse[i]) continue;
        any = true;
        for (int t : components[i].triangles) flipTriangle(mesh.triangles[t]);
        components[i].volume = -components[i].volume;
    }
    return any;
}

} // namespace

MeshValidationReport validateSolidMesh(TriangleMesh& mesh, const std::string& source)
{
    MeshValidationReport report;
    checkIndicesAndCoordinates(mesh, source);
    report.removedDegenerateTriangles = removeDegenerateTriangles(mesh, source);
    std::vector<Component> components;
    {
        const std::vector<Neighbours> neighbours =
            findNeighbours(mesh, source, report.removedDegenerateTriangles);
        components = orientComponents(mesh, neighbours, source, report.reorientedTriangles);
    }  // (the neighbours are not needed past here)

    const auto bounds = meshBounds(mesh);
    measureComponents(mesh, 0.5 * (bounds[0] + bounds[1]), components);
    checkPartsApart(mesh, components, source);
    report.flippedToOutward = orientOutward(mesh, components);

    // A flat or doubled part bounds nothing, whatever the rest of the mesh does.
    for (const Component& comp : components) {
        const double size = (comp.hi - comp.lo).norm();
        if (!(std::abs(comp.volume) > 1e-12 * size * size * size))
            throw Error(source,
                        "a part of the surface (" +
                            countOf(static_cast<int>(comp.triangles.size()), "triangle") +
                            ") encloses no volume",
                        "remove flat or doubled parts: the mesh must be the closed surface of "
                        "a solid");
    }
    double volume = 0.0;
    for (const Component& comp : components) volume += comp.volume;
    if (!(volume > 0.0))
        throw Error(source,
                    "the surface encloses no volume (signed volume " + numberText(volume) +
                        ")",
                    "check that the mesh is the closed surface of a solid, not a sheet or a "
                    "doubled surface");
    return report;
}

void appendRepairWarnings(const MeshValidationReport& report, const std::string& source,
                          std::vector<std::string>& warnings)
{
    if (report.removedDegenerateTriangles > 0)
        warnings.push_back(source + ": dropped " +
                           std::to_string(report.removedDegenerateTriangles) +
                           " degenerate (zero-area) triangles");
    if (report.reorientedTriangles > 0)
        warnings.push_back(source + ": flipped " + std::to_string(report.reorientedTriangles) +
                           " triangles to agree with their neighbours");
    if (report.flippedToOutward)
        warnings.push_back(source + ": the mesh was inside-out; reversed it to face outward");
}

} // namespace lsdem
