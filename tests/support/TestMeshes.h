/// @file TestMeshes.h
/// @brief Small closed meshes built independently of the library (no AnalyticShape), for the
///        mesh tests: an axis-aligned box, a subdivided icosahedron, parts merged or turned
///        inside out, and the signed volume.
#pragma once

#include "lsdem/mesh/TriangleMesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace lsdem::test {

/// Axis-aligned box from @a lo to @a hi: 8 vertices, 12 outward triangles.
inline TriangleMesh makeBox(const Vec3& lo, const Vec3& hi)
{
    TriangleMesh mesh;
    for (int i = 0; i < 8; ++i)
        mesh.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                                   i & 4 ? hi.z() : lo.z());
    const Vec3 centre = 0.5 * (lo + hi);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // The four corners of this face in cyclic order: bits of the two other axes.
            const int b = 1 << ((axis + 1) % 3), c = 1 << ((axis + 2) % 3), a = side << axis;
            const std::array<int, 4> quad{a, a | b, a | b | c, a | c};
            for (const auto& tri : {std::array<int, 3>{quad[0], quad[1], quad[2]},
                                    std::array<int, 3>{quad[0], quad[2], quad[3]}}) {
                const Vec3& p = mesh.vertices[tri[0]];
                const Vec3 n = (mesh.vertices[tri[1]] - p).cross(mesh.vertices[tri[2]] - p);
                // Outward means the normal points away from the centre.
                if (n.dot(p - centre) > 0) mesh.triangles.push_back(tri);
                else mesh.triangles.push_back({tri[0], tri[2], tri[1]});
            }
        }
    return mesh;
}

/// Unit sphere: an icosahedron subdivided @a levels times, vertices pushed onto the sphere.
inline TriangleMesh makeIcosphere(int levels)
{
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    TriangleMesh mesh;
    for (double s : {-1.0, 1.0})
        for (double t : {-phi, phi}) {
            mesh.vertices.emplace_back(s, t, 0.0);
            mesh.vertices.emplace_back(0.0, s, t);
            mesh.vertices.emplace_back(t, 0.0, s);
        }
    // The faces are the triples of mutually adjacent vertices (edge length 2), made outward.
    auto adjacent = [&](int i, int j) {
        return std::abs((mesh.vertices[i] - mesh.vertices[j]).squaredNorm() - 4.0) < 1e-9;
    };
    for (int i = 0; i < 12; ++i)
        for (int j = i + 1; j < 12; ++j)
            for (int k = j + 1; k < 12; ++k) {
                if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
                const Vec3& a = mesh.vertices[i];
                const Vec3 n = (mesh.vertices[j] - a).cross(mesh.vertices[k] - a);
                if (n.dot(a) > 0) mesh.triangles.push_back({i, j, k});
                else mesh.triangles.push_back({i, k, j});
            }
    for (Vec3& v : mesh.vertices) v.normalize();
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<int, int>, int> midpoints;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            mesh.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
            const int id = static_cast<int>(mesh.vertices.size()) - 1;
            midpoints.emplace(key, id);
            return id;
        };
        std::vector<std::array<int, 3>> finer;
        for (const auto& t : mesh.triangles) {
            const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]);
            const int ca = midpoint(t[2], t[0]);
            finer.push_back({t[0], ab, ca});
            finer.push_back({t[1], bc, ab});
            finer.push_back({t[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        mesh.triangles = finer;
    }
    return mesh;
}

/// @a b appended to @a a, with vertices of equal position shared.
inline TriangleMesh mergeWelded(const TriangleMesh& a, const TriangleMesh& b)
{
    TriangleMesh out;
    std::map<std::array<double, 3>, int> index;
    auto add = [&](const TriangleMesh& part) {
        for (const auto& t : part.triangles) {
            std::array<int, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = part.vertices[size_t(t[k])];
                const auto found = index.emplace(std::array<double, 3>{p.x(), p.y(), p.z()},
                                                 static_cast<int>(out.vertices.size()));
                if (found.second) out.vertices.push_back(p);
                tri[k] = found.first->second;
            }
            out.triangles.push_back(tri);
        }
    };
    add(a);
    add(b);
    return out;
}

/// @a mesh with every triangle turned the other way (a cavity's surface, from a solid's).
inline TriangleMesh reversed(TriangleMesh mesh)
{
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

inline double signedVolume(const TriangleMesh& mesh)
{
    double sum = 0.0;
    for (const auto& t : mesh.triangles)
        sum += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
    return sum / 6.0;
}

} // namespace lsdem::test
