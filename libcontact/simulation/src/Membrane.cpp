// The membrane's own mechanics (Membrane.h): reference shapes, the constant-strain triangles'
// forces with tension-field wrinkling, the follower pressure, the enclosed volume and the
// stable step. Its contacts with grains are in MembraneContact.cpp.
#include "lsdem/simulation/Membrane.h"
#include "lsdem/simulation/StableStep.h"

#include "lsdem/core/Error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace lsdem {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Rims: the directed edges only one triangle has, grouped into connected loops.
void findRims(Membrane& m)
{
    std::map<std::pair<int, int>, int> edgeUses;  // undirected edge → triangles that have it
    for (const MembraneTriangle& t : m.triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t.vertices[k], b = t.vertices[(k + 1) % 3];
            ++edgeUses[{std::min(a, b), std::max(a, b)}];
        }
    m.rimEdges.clear();
    for (const MembraneTriangle& t : m.triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t.vertices[k], b = t.vertices[(k + 1) % 3];
            if (edgeUses[{std::min(a, b), std::max(a, b)}] == 1) m.rimEdges.push_back({a, b});
        }
    // Union-find over the rims' vertices: each connected loop is one rim.
    std::vector<int> parent(m.positions.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int v) {
        while (parent[size_t(v)] != v) v = parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
        return v;
    };
    for (const auto& e : m.rimEdges) parent[size_t(root(e[0]))] = root(e[1]);
    std::map<int, int> rimOfRoot;
    m.rimOfEdge.clear();
    for (const auto& e : m.rimEdges) {
        const auto found = rimOfRoot.emplace(root(e[0]), static_cast<int>(rimOfRoot.size()));
        m.rimOfEdge.push_back(found.first->second);
    }
    m.rimCount = static_cast<int>(rimOfRoot.size());
}

/// The triangle's deformation gradient (3×2: its reference frame to the world).
Eigen::Matrix<double, 3, 2> deformationGradient(const Membrane& m, const MembraneTriangle& t)
{
    Eigen::Matrix<double, 3, 2> edges;
    const Vec3& x0 = m.positions[size_t(t.vertices[0])];
    edges.col(0) = m.positions[size_t(t.vertices[1])] - x0;
    edges.col(1) = m.positions[size_t(t.vertices[2])] - x0;
    return edges * t.inverseShape;
}

/// The second Piola–Kirchhoff stress of Green strain @a e (plane stress, St Venant–Kirchhoff)
/// with tension-field wrinkling, and its strain energy per reference volume.
/// @a e1 receives the largest principal strain.
Eigen::Matrix2d wrinklingStress(const MembraneMaterial& rubber, const Eigen::Matrix2d& e,
                                double& energyDensity, double& e1)
{
    const double E = rubber.youngs, nu = rubber.poisson;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> principal(e);
    e1 = principal.eigenvalues()[1];
    const double e2 = principal.eigenvalues()[0];  // e1 ≥ e2
    if (e1 <= 0.0) {  // slack: compressed every way, it folds
        energyDensity = 0.0;
        return Eigen::Matrix2d::Zero();
    }
    const double factor = E / (1.0 - nu * nu);
    if (e2 + nu * e1 >= 0.0) {  // taut: both principal stresses ≥ 0
        const double trace = e.trace();
        const Eigen::Matrix2d s =
            factor * ((1.0 - nu) * e + nu * trace * Eigen::Matrix2d::Identity());
        energyDensity = 0.5 * (s.array() * e.array()).sum();
        return s;
    }
    // Wrinkled: it stretches along e1's direction only, uniaxially (σ₂ = 0), σ₁ = E·e1.
    const Eigen::Vector2d n1 = principal.eigenvectors().col(1);
    energyDensity = 0.5 * E * e1 * e1;
    return E * e1 * n1 * n1.transpose();
}

/// Green strain of a triangle now.
Eigen::Matrix2d greenStrain(const Eigen::Matrix<double, 3, 2>& f)
{
    return 0.5 * (f.transpose() * f - Eigen::Matrix2d::Identity());
}

/// A bound on ω² of triangle @a t's vertices on its own stiffness, at largest principal Green
/// strain @a e1. With lumped masses ρ·t·A/3 and stiffness t·A·BᵀCB (A, B of the unstretched
/// triangle), ω² ≤ 3/(ρ·t·A)·t·A·λmax(C)·trace(BᵀB) = 3·E/(1−ν)/ρ·2·Σ|∇Nᵢ|²; the whole
/// shell's ω² is at most its triangles' largest. Stretched, St Venant–Kirchhoff's tangent
/// grows by at most 1 + 3·e1 (compressed it only softens, and a slack triangle has none). The
/// follower pressure adds a load stiffness of at most (2/3)·p·ℓmax per vertex, ℓmax its
/// longest edge now.
double triangleOmegaSquared(const Membrane& m, const MembraneTriangle& t, double e1)
{
    const MembraneMaterial& r = m.rubber;
    // The shape functions' gradients in the triangle's own frame: ∇N₁, ∇N₂ the rows of the
    // inverse shape, ∇N₀ = −∇N₁ − ∇N₂.
    const Eigen::Vector2d g1 = t.inverseShape.row(0), g2 = t.inverseShape.row(1);
    const double gradients = g1.squaredNorm() + g2.squaredNorm() + (g1 + g2).squaredNorm();
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
        longest = std::max(longest, (m.positions[size_t(t.vertices[k])] -
                                     m.positions[size_t(t.vertices[(k + 1) % 3])]).norm());
    const double elastic = 3.0 * r.youngs / (1.0 - r.poisson) / r.density * 2.0 * gradients *
                           (1.0 + 3.0 * std::max(0.0, e1));
    const double load =
        2.0 / 3.0 * std::abs(m.pressure) * longest / (r.density * r.thickness * t.area / 3.0);
    return elastic + load;
}

} // namespace

void finishMembrane(Membrane& m)
{
    const MembraneMaterial& r = m.rubber;
    const std::string where = "membrane '" + m.name + "'";
    if (!(r.youngs > 0.0) || !std::isfinite(r.youngs))
        throw Error(where, "Young's modulus must be positive and finite", "give youngs > 0");
    if (!(r.poisson >= 0.0 && r.poisson < 0.5))
        throw Error(where, "Poisson's ratio must lie in [0, 0.5)", "rubber is near 0.5: give 0.45-0.49");
    if (!(r.thickness > 0.0) || !std::isfinite(r.thickness))
        throw Error(where, "the thickness must be positive and finite", "give thickness > 0");
    if (!(r.density > 0.0) || !std::isfinite(r.density))
        throw Error(where, "the density must be positive and finite", "give density > 0");
    if (m.triangles.empty()) throw Error(where, "it has no triangles");
    m.masses.assign(m.positions.size(), 0.0);
    m.velocities.resize(m.positions.size(), Vec3::Zero());
    m.heldBy.resize(m.positions.size(), -1);
    m.forces.assign(m.positions.size(), Vec3::Zero());
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        MembraneTriangle& t = m.triangles[i];
        for (int v : t.vertices)
            if (v < 0 || size_t(v) >= m.positions.size())
                throw Error(where, "triangle " + std::to_string(i) + " names a vertex it does not have");
        const Vec3& x0 = m.positions[size_t(t.vertices[0])];
        const Vec3 a = m.positions[size_t(t.vertices[1])] - x0;
        const Vec3 b = m.positions[size_t(t.vertices[2])] - x0;
        const double area = 0.5 * a.cross(b).norm();
        if (!(area > 1e-12 * std::max(a.squaredNorm(), b.squaredNorm())))
            throw Error(where, "triangle " + std::to_string(i) + " has no area",
                        "remove degenerate triangles");
        // Its own frame: u along edge a, v in its plane, so the edges are (|a|, 0) and (b·u, b·v).
        const Vec3 u = a.normalized();
        const Vec3 v = (b - b.dot(u) * u).normalized();
        Eigen::Matrix2d shape;
        shape << a.norm(), b.dot(u), 0.0, b.dot(v);
        t.inverseShape = shape.inverse();
        t.area = area;
        const double third = r.density * r.thickness * area / 3.0;
        for (int vtx : t.vertices) m.masses[size_t(vtx)] += third;
    }
    findRims(m);
    double edges = 0.0;
    for (const MembraneTriangle& t : m.triangles)
        for (int k = 0; k < 3; ++k)
            edges += (m.positions[size_t(t.vertices[k])] - m.positions[size_t(t.vertices[(k + 1) % 3])]).norm();
    m.contactReach = 0.25 * edges / (3.0 * static_cast<double>(m.triangles.size()));
}

Membrane makeTubeMembrane(const Vec3& base, const Vec3& axis, double radius, double height,
                          int segments, int rings, const MembraneMaterial& rubber,
                          double prestretch)
{
    if (!(radius > 0.0) || !(height > 0.0) || segments < 3 || rings < 1)
        throw Error("tube membrane", "its radius and height must be positive, with at least 3 "
                                     "segments and 1 ring of triangles");
    if (!(prestretch >= 1.0 && std::isfinite(prestretch)))
        throw Error("tube membrane", "its prestretch must be at least 1 (got " +
                                         std::to_string(prestretch) + ")",
                    "1 puts it on unstretched; 1.05 stretches it 5 % round");
    Membrane m;
    m.rubber = rubber;
    const Vec3 z = axis.normalized();
    // Two directions across the axis, right-handed with it: (x, y, z).
    const Vec3 x = (std::abs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(z).normalized();
    const Vec3 y = z.cross(x);
    for (int j = 0; j <= rings; ++j)
        for (int i = 0; i < segments; ++i) {
            const double angle = 2.0 * kPi * i / segments;
            m.positions.push_back(base + height * j / rings * z +
                                  radius / prestretch * (std::cos(angle) * x + std::sin(angle) * y));
        }
    auto vertex = [&](int i, int j) { return j * segments + (i % segments); };
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            // Round the axis (counter-clockwise about z), then along it: e_θ × e_z points out.
            // The diagonal alternates ring by ring, so the shell has no handedness.
            const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                      d = vertex(i, j + 1);
            MembraneTriangle t1, t2;
            if (j % 2 == 0) {
                t1.vertices = {a, b, c};
                t2.vertices = {a, c, d};
            } else {
                t1.vertices = {a, b, d};
                t2.vertices = {b, c, d};
            }
            m.triangles.push_back(t1);
            m.triangles.push_back(t2);
        }
    finishMembrane(m);  // (its reference shapes the unstretched tube's) ...
    for (Vec3& p : m.positions) {  // ... then stretched round to the radius as placed
        const Vec3 out = (p - base) - (p - base).dot(z) * z;
        p += (prestretch - 1.0) * out;
    }
    return m;
}

void computeMembraneForces(Membrane& m, std::vector<Vec3>* pressureForces)
{
    m.forces.assign(m.positions.size(), Vec3::Zero());
    if (pressureForces) pressureForces->assign(m.positions.size(), Vec3::Zero());
    const double t = m.rubber.thickness;
    double energy = 0.0, omegaSquared = 0.0;
    for (const MembraneTriangle& tri : m.triangles) {
        const Eigen::Matrix<double, 3, 2> f = deformationGradient(m, tri);
        const Eigen::Matrix2d e = greenStrain(f);
        double density = 0.0, e1 = 0.0;
        const Eigen::Matrix2d s = wrinklingStress(m.rubber, e, density, e1);
        energy += density * tri.area * t;
        omegaSquared = std::max(omegaSquared, triangleOmegaSquared(m, tri, e1));
        // −∂W/∂(edge vectors): the first Piola–Kirchhoff stress F·S over the reference
        // volume, pulled back through the reference shape.
        const Eigen::Matrix<double, 3, 2> h =
            -tri.area * t * (f * s) * tri.inverseShape.transpose();
        const Vec3 f1 = h.col(0), f2 = h.col(1);
        m.forces[size_t(tri.vertices[1])] += f1;
        m.forces[size_t(tri.vertices[2])] += f2;
        m.forces[size_t(tri.vertices[0])] -= f1 + f2;
        if (m.pressure != 0.0) {
            const Vec3& x0 = m.positions[size_t(tri.vertices[0])];
            const Vec3 areaVector = 0.5 * (m.positions[size_t(tri.vertices[1])] - x0)
                                              .cross(m.positions[size_t(tri.vertices[2])] - x0);
            const Vec3 share = -m.pressure / 3.0 * areaVector;
            for (int v : tri.vertices) {
                m.forces[size_t(v)] += share;
                if (pressureForces) (*pressureForces)[size_t(v)] += share;
            }
        }
    }
    m.strainEnergy = energy;
    m.rubberOmegaSquared = omegaSquared;
}

std::vector<Vec3> rimCentroids(const Membrane& m)
{
    std::vector<Vec3> centroid(size_t(m.rimCount), Vec3::Zero());
    std::vector<int> count(size_t(m.rimCount), 0);
    for (size_t k = 0; k < m.rimEdges.size(); ++k) {  // (each rim vertex starts one edge)
        centroid[size_t(m.rimOfEdge[k])] += m.positions[size_t(m.rimEdges[k][0])];
        ++count[size_t(m.rimOfEdge[k])];
    }
    for (int r = 0; r < m.rimCount; ++r) centroid[size_t(r)] /= count[size_t(r)];
    return centroid;
}

double enclosedVolume(const Membrane& m)
{
    // Σ over closed faces of x₀·(x₁ × x₂)/6: the triangles, then each rim edge's fan triangle
    // (centroid, b, a) closing the rims (its edge run backwards, so the fan faces out too).
    double sixVolume = 0.0;
    for (const MembraneTriangle& t : m.triangles)
        sixVolume += m.positions[size_t(t.vertices[0])].dot(
            m.positions[size_t(t.vertices[1])].cross(m.positions[size_t(t.vertices[2])]));
    const std::vector<Vec3> centroid = rimCentroids(m);
    for (size_t k = 0; k < m.rimEdges.size(); ++k) {
        const Vec3& c = centroid[size_t(m.rimOfEdge[k])];
        sixVolume += c.dot(m.positions[size_t(m.rimEdges[k][1])].cross(
            m.positions[size_t(m.rimEdges[k][0])]));
    }
    return sixVolume / 6.0;
}

double membraneKineticEnergy(const Membrane& m)
{
    double energy = 0.0;
    for (size_t i = 0; i < m.positions.size(); ++i)
        if (m.heldBy[i] < 0) energy += 0.5 * m.masses[i] * m.velocities[i].squaredNorm();
    return energy;
}

double membraneRubberOmegaSquared(const Membrane& m)
{
    double omegaSquared = 0.0;
    for (const MembraneTriangle& t : m.triangles) {
        const Eigen::Matrix2d e = greenStrain(deformationGradient(m, t));
        const double e1 =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(e, Eigen::EigenvaluesOnly).eigenvalues()[1];
        omegaSquared = std::max(omegaSquared, triangleOmegaSquared(m, t, e1));
    }
    return omegaSquared;
}

double membraneStableStep(const Membrane& m, double globalDamping)
{
    return dampedStableStep(membraneRubberOmegaSquared(m), membraneDragRate(m), globalDamping);
}

double membraneDragRate(const Membrane& m)
{
    return m.drag > 0.0 ? m.drag / (m.rubber.density * m.rubber.thickness) : 0.0;
}

} // namespace lsdem
