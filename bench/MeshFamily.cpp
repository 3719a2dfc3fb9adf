#include "MeshFamily.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/PortableRandom.h"
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/GrainGenerator.h"

#include <cmath>
#include <stdexcept>

namespace lsdem::bench {

namespace {

/// A unit icosphere of frequency @a n (20·n² triangles, edges about 1.05/n).
TriangleMesh unitIcosphere(int n)
{
    return AnalyticShape::sphere(1.0).surfaceMesh(1.05 / n);
}

/// Each vertex of a unit sphere mesh moved to radius(u) along its direction u.
template <class Radius>
TriangleMesh radialGraph(TriangleMesh mesh, Radius radius)
{
    for (Vec3& v : mesh.vertices) {
        const Vec3 u = v.normalized();
        v = radius(u) * u;
    }
    return mesh;
}

/// A latitude–longitude sphere of radius 5: @a rings bands of @a sectors quads, fans at the
/// poles, so the triangles next to the poles are needles.
TriangleMesh uvSphere(int rings, int sectors)
{
    TriangleMesh mesh;
    const double radius = 5.0;
    mesh.vertices.emplace_back(0.0, 0.0, radius);  // north pole, 0
    for (int i = 1; i < rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j < sectors; ++j) {
            const double phi = 2.0 * kPi * j / sectors;
            mesh.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi),
                                       radius * std::sin(theta) * std::sin(phi),
                                       radius * std::cos(theta));
        }
    }
    const int south = int(mesh.vertices.size());
    mesh.vertices.emplace_back(0.0, 0.0, -radius);
    auto at = [sectors](int ring, int j) { return 1 + (ring - 1) * sectors + (j % sectors); };
    for (int j = 0; j < sectors; ++j) mesh.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    for (int j = 0; j < sectors; ++j)
        mesh.triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
    return mesh;
}

/// A unit-sphere point moved by the conformal map that scales the stereographic plane by @a k:
/// lengths grow by about k near the south pole and shrink by 1/k near the north pole, so
/// triangle areas vary by k⁴ while keeping their shapes.
Vec3 stretchStereographic(const Vec3& u, double k)
{
    if (u.z() > 1.0 - 1e-15) return u;
    const double px = k * u.x() / (1.0 - u.z()), py = k * u.y() / (1.0 - u.z());
    const double r2 = px * px + py * py;
    return Vec3(2.0 * px, 2.0 * py, r2 - 1.0) / (r2 + 1.0);
}

} // namespace

FamilyMesh familyMesh(int index)
{
    switch (index) {
    case 0:
        return {"pebble", radialGraph(unitIcosphere(71), [](const Vec3& u) {
                    return 5.0 * (1.0 + 0.08 * std::sin(3 * u.x()) * std::cos(2 * u.y()) +
                                  0.05 * std::sin(5 * u.z() + 1.0));
                })};
    case 1:
        return {"bumpy", radialGraph(unitIcosphere(64), [](const Vec3& u) {
                    return 5.0 * (1.0 + 0.13 * std::sin(4 * u.x() + 0.5) *
                                            std::sin(3 * u.y() + 1.0) * std::cos(2 * u.z()));
                })};
    case 2: {
        GrainShapeOptions o;
        o.size = 10.0;
        o.triangles = 100000;
        return {"grain", generateGrain(o, 1, 0)};
    }
    case 3: return {"uv-sphere", uvSphere(160, 320)};
    case 4: {
        TriangleMesh mesh = unitIcosphere(64);
        for (Vec3& v : mesh.vertices) v = 5.0 * stretchStereographic(v.normalized(), std::sqrt(10.0));
        return {"graded", mesh};
    }
    case 5:
        return {"peanut", radialGraph(unitIcosphere(64), [](const Vec3& u) {
                    const double waist = 0.7 + 0.45 * (2.0 * u.z() * u.z() - 1.0);  // cos 2θ
                    return 5.0 * waist * (1.0 + 0.04 * std::sin(7 * u.x()) * std::cos(5 * u.y()));
                })};
    case 6: {
        // A scan's noise: the grain's vertices moved at random along their radius by up to
        // ±0.3 % of its size (0.03 on d = 10, half its edges' length): many edges turn sharp.
        FamilyMesh member = familyMesh(2);
        for (size_t i = 0; i < member.mesh.vertices.size(); ++i) {
            const double draw = double(splitMix64(i + 1) >> 11) * 0x1.0p-53;  // [0, 1)
            Vec3& v = member.mesh.vertices[i];
            v *= 1.0 + 0.006 * (draw - 0.5) * 10.0 / v.norm();
        }
        return {"noisy", member.mesh};
    }
    }
    throw std::out_of_range("familyMesh: no member " + std::to_string(index));
}

void warmUpProcess()
{
    static const bool warmed = [] {
        std::vector<std::string> warnings;
        bakeMesh(radialGraph(unitIcosphere(16), [](const Vec3&) { return 1.0; }), "warm-up",
                 familyBakeOptions(), warnings);
        return true;
    }();
    (void)warmed;
}

BakeOptions familyBakeOptions()
{
    BakeOptions o;
    o.voxelSize = 0.05;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = 0.12;
    return o;
}

} // namespace lsdem::bench
