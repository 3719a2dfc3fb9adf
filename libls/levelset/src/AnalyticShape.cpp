#include "lsdem/ls/AnalyticShape.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GaussLegendre.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace lsdem {

namespace {

void requirePositive(const Vec3& size, const char* what)
{
    for (int k = 0; k < 3; ++k)
        if (!(size[k] > 0.0) || !std::isfinite(size[k]))
            throw Error("", std::string(what) + " dimensions must be positive and finite",
                        "give lengths > 0 in your length unit");
}

/// Closest point to @a p on the ellipsoid with semi-axes @a e: x_i = e_i² p_i / (t + e_i²) where t
/// is the root of F(t) = Σ (e_i p_i / (t + e_i²))² - 1, strictly decreasing on (-min e_i², ∞).
/// We solve for s = t + min e_i² > 0 so that s + (e_i² - e_min²) keeps full precision when the
/// root is close to the pole (points near the centre). Zero coordinates are nudged by a tiny ε
/// (the distance is 1-Lipschitz, so this moves it by at most ε) to keep the root unique.
Vec3 closestPointOnEllipsoid(const Vec3& p, const Vec3& e)
{
    const double eps = 1e-12 * e.maxCoeff();
    Vec3 y, sign;
    for (int k = 0; k < 3; ++k) {
        sign[k] = p[k] < 0.0 ? -1.0 : 1.0;
        y[k] = std::max(std::abs(p[k]), eps);
    }
    const Vec3 e2 = e.cwiseProduct(e);
    int kMin;
    const double e2Min = e2.minCoeff(&kMin);
    const Vec3 shift = e2.array() - e2Min;  // exact: t + e_i² = s + shift_i
    auto f = [&](double s, double& slope) {
        double value = -1.0;
        slope = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double r = e[k] * y[k] / (s + shift[k]);
            value += r * r;
            slope += -2.0 * r * r / (s + shift[k]);
        }
        return value;
    };
    double lo = 0.5 * e[kMin] * y[kMin];       // there the kMin term alone is 4: F > 0
    double hi = e.maxCoeff() * y.norm() + e2Min;  // there every term is below 1/|y|²·y_i²: F <= 0
    double s = 0.5 * (lo + hi);
    for (int iter = 0; iter < 200; ++iter) {
        double slope;
        const double value = f(s, slope);
        if (value > 0.0) lo = s; else hi = s;
        double next = s - value / slope;  // Newton, kept inside the bracket
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const bool converged = std::abs(next - s) <= 1e-15 * s;
        s = next;
        if (converged || hi - lo <= 1e-16 * hi) break;
    }
    Vec3 x;
    for (int k = 0; k < 3; ++k) x[k] = sign[k] * e2[k] * y[k] / (s + shift[k]);
    return x;
}

/// A unit icosphere: the icosahedron with each face cut into n^2 triangles, projected.
TriangleMesh unitIcosphere(int n)
{
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    const std::vector<Vec3> ico = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0},
                                   {0, -1, g}, {0, 1, g},  {0, -1, -g}, {0, 1, -g},
                                   {g, 0, -1}, {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    TriangleMesh mesh;
    // Vertices are shared between faces by their exact barycentric lattice position.
    std::map<std::array<long long, 3>, int> index;
    auto vertexAt = [&](const Vec3& p) {
        const std::array<long long, 3> key = {std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                              std::llround(p.z() * 1e9)};
        auto it = index.find(key);
        if (it != index.end()) return it->second;
        mesh.vertices.push_back(p.normalized());
        index.emplace(key, static_cast<int>(mesh.vertices.size()) - 1);
        return static_cast<int>(mesh.vertices.size()) - 1;
    };
    for (const auto& f : faces) {
        const Vec3 a = ico[f[0]], b = ico[f[1]], c = ico[f[2]];
        auto lattice = [&](int i, int j) {  // i steps toward b, j toward c
            return vertexAt(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                mesh.triangles.push_back({lattice(i, j), lattice(i + 1, j), lattice(i, j + 1)});
                if (i + j + 1 < n)
                    mesh.triangles.push_back(
                        {lattice(i + 1, j), lattice(i + 1, j + 1), lattice(i, j + 1)});
            }
    }
    return mesh;
}

/// A box surface as a structured grid of right triangles, about @a h apart, shared edges.
TriangleMesh boxSurface(const Vec3& half, double h)
{
    int count[3];
    // The small slack keeps exact multiples (6 / 0.1 = 60.000000000000007) from gaining a row.
    for (int k = 0; k < 3; ++k)
        count[k] = std::max(1, static_cast<int>(std::ceil(2 * half[k] / h - 1e-9)));
    TriangleMesh mesh;
    std::map<std::array<int, 3>, int> index;
    auto vertexAt = [&](std::array<int, 3> ijk) {
        auto it = index.find(ijk);
        if (it != index.end()) return it->second;
        Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = -half[k] + 2 * half[k] * ijk[k] / count[k];
        mesh.vertices.push_back(p);
        index.emplace(ijk, static_cast<int>(mesh.vertices.size()) - 1);
        return static_cast<int>(mesh.vertices.size()) - 1;
    };
    for (int axis = 0; axis < 3; ++axis) {
        // (axis, u, v) cyclic so that e_u x e_v = e_axis: counter-clockwise seen from +axis.
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            for (int i = 0; i < count[u]; ++i)
                for (int j = 0; j < count[v]; ++j) {
                    auto corner = [&](int di, int dj) {
                        std::array<int, 3> ijk{};
                        ijk[axis] = side ? count[axis] : 0;
                        ijk[u] = i + di;
                        ijk[v] = j + dj;
                        return vertexAt(ijk);
                    };
                    const int a = corner(0, 0), b = corner(1, 0), c = corner(1, 1),
                              d = corner(0, 1);
                    if (side) {
                        mesh.triangles.push_back({a, b, c});
                        mesh.triangles.push_back({a, c, d});
                    } else {
                        mesh.triangles.push_back({a, c, b});
                        mesh.triangles.push_back({a, d, c});
                    }
                }
        }
    }
    return mesh;
}

} // namespace

AnalyticShape AnalyticShape::sphere(double radius)
{
    AnalyticShape s;
    s.kind = Kind::Sphere;
    s.size = Vec3::Constant(radius);
    requirePositive(s.size, "sphere");
    return s;
}

AnalyticShape AnalyticShape::box(double a, double b, double c)
{
    AnalyticShape s;
    s.kind = Kind::Box;
    s.size = Vec3(a, b, c);
    requirePositive(s.size, "box");
    return s;
}

AnalyticShape AnalyticShape::ellipsoid(double a, double b, double c)
{
    AnalyticShape s;
    s.kind = Kind::Ellipsoid;
    s.size = Vec3(a, b, c);
    requirePositive(s.size, "ellipsoid");
    return s;
}

Vec3 AnalyticShape::halfExtents() const
{
    return kind == Kind::Box ? Vec3(0.5 * size) : size;
}

double AnalyticShape::signedDistance(const Vec3& p) const
{
    switch (kind) {
    case Kind::Sphere: return p.norm() - size.x();
    case Kind::Box: {
        const Vec3 q = p.cwiseAbs() - halfExtents();
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case Kind::Ellipsoid: {
        const double d = (p - closestPointOnEllipsoid(p, size)).norm();
        return p.cwiseQuotient(size).squaredNorm() < 1.0 ? -d : d;
    }
    }
    return 0.0;
}

namespace {

/// An analytic shape's distance; its gradient points from the closest surface point to the
/// point, outwards on either side (the surface's normal on it).
class ShapeDistance final : public ExactDistance
{
public:
    explicit ShapeDistance(const AnalyticShape& shape) : mShape(shape) {}
    double phi(const Vec3& p) const override { return mShape.signedDistance(p); }
    Vec3 gradient(const Vec3& p) const override
    {
        const Vec3 closest = mShape.closestSurfacePoint(p);
        const double d = mShape.signedDistance(p);
        // Within a hair of the surface p − closest is round-off (a node on the surface has
        // φ of an ulp or 0): the surface's normal there is the gradient to O(|φ|·curvature).
        const double hair = 1e-8 * mShape.halfExtents().maxCoeff();
        return std::abs(d) > hair ? Vec3((p - closest) / d) : mShape.outwardNormal(closest);
    }

private:
    AnalyticShape mShape;
};

} // namespace

std::shared_ptr<const ExactDistance> AnalyticShape::exactDistance() const
{
    return std::make_shared<ShapeDistance>(*this);
}

Vec3 AnalyticShape::closestSurfacePoint(const Vec3& p) const
{
    switch (kind) {
    case Kind::Sphere: {
        const double r = p.norm();
        return r > 0.0 ? Vec3(p * (size.x() / r)) : Vec3(size.x(), 0, 0);
    }
    case Kind::Box: {
        const Vec3 h = halfExtents();
        const Vec3 q = p.cwiseAbs() - h;
        if (q.maxCoeff() > 0.0) return p.cwiseMax(-h).cwiseMin(h);  // outside: clamp
        int axis;
        q.maxCoeff(&axis);  // inside: the nearest face
        Vec3 x = p;
        x[axis] = p[axis] < 0.0 ? -h[axis] : h[axis];
        return x;
    }
    case Kind::Ellipsoid: return closestPointOnEllipsoid(p, size);
    }
    return p;
}

Vec3 AnalyticShape::outwardNormal(const Vec3& x) const
{
    switch (kind) {
    case Kind::Sphere: return x.normalized();
    case Kind::Box: {
        const Vec3 h = halfExtents();
        Vec3 n = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
            if (std::abs(std::abs(x[k]) - h[k]) <= 1e-9 * h.maxCoeff()) n[k] = x[k] < 0 ? -1 : 1;
        return n.squaredNorm() > 0 ? n.normalized() : Vec3::UnitZ();
    }
    case Kind::Ellipsoid: return x.cwiseQuotient(size.cwiseProduct(size)).normalized();
    }
    return Vec3::UnitZ();
}

double AnalyticShape::surfaceArea() const
{
    switch (kind) {
    case Kind::Sphere: return 4.0 * kPi * size.x() * size.x();
    case Kind::Box:
        return 2.0 * (size.x() * size.y() + size.y() * size.z() + size.z() * size.x());
    case Kind::Ellipsoid: {
        // Area = ∫_{-1}^{1} ∫_0^{2π} sqrt(b²c²(1-u²)cos²φ + a²c²(1-u²)sin²φ + a²b²u²) dφ du
        // (u = cos θ): smooth in u (Gauss–Legendre) and periodic in φ (trapezoid rule), so
        // both rules converge exponentially.
        const double a = size.x(), b = size.y(), c = size.z();
        std::vector<double> x, w;
        gaussLegendre(96, x, w);
        const int nPhi = 256;
        double area = 0.0;
        for (int i = 0; i < 96; ++i) {
            const double u = x[i], s2 = 1.0 - u * u;
            double ring = 0.0;
            for (int j = 0; j < nPhi; ++j) {
                const double phi = 2.0 * kPi * j / nPhi;
                const double cp = std::cos(phi), sp = std::sin(phi);
                ring += std::sqrt(b * b * c * c * s2 * cp * cp + a * a * c * c * s2 * sp * sp +
                                  a * a * b * b * u * u);
            }
            area += w[i] * ring * (2.0 * kPi / nPhi);
        }
        return area;
    }
    }
    return 0.0;
}

MassProperties AnalyticShape::massProperties() const
{
    MassProperties props;
    const double a = size.x(), b = size.y(), c = size.z();
    Vec3 moments = Vec3::Zero();
    switch (kind) {
    case Kind::Sphere:
        props.volume = 4.0 / 3.0 * kPi * a * a * a;
        moments = Vec3::Constant(0.4 * props.volume * a * a);
        break;
    case Kind::Box:
        props.volume = a * b * c;
        moments = props.volume / 12.0 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b);
        break;
    case Kind::Ellipsoid:
        props.volume = 4.0 / 3.0 * kPi * a * b * c;
        moments = props.volume / 5.0 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b);
        break;
    }
    props.inertia = moments.asDiagonal();
    return props;
}

TriangleMesh AnalyticShape::surfaceMesh(double edgeLength) const
{
    if (!(edgeLength > 0.0)) throw Error("", "surface mesh edge length must be positive");
    if (kind == Kind::Box) return boxSurface(halfExtents(), edgeLength);
    // Icosphere edges are about 1.05/n on the unit sphere; size n for the longest semi-axis.
    const int n = std::max(2, static_cast<int>(std::ceil(1.05 * size.maxCoeff() / edgeLength)));
    TriangleMesh mesh = unitIcosphere(n);
    for (Vec3& v : mesh.vertices) v = closestSurfacePoint(v.cwiseProduct(size));
    return mesh;
}

std::string AnalyticShape::describe() const
{
    std::ostringstream out;
    out.precision(10);
    switch (kind) {
    case Kind::Sphere: out << "sphere R=" << size.x(); break;
    case Kind::Box: out << "box " << size.x() << "x" << size.y() << "x" << size.z(); break;
    case Kind::Ellipsoid:
        out << "ellipsoid semi-axes " << size.x() << "," << size.y() << "," << size.z();
        break;
    }
    return out.str();
}

} // namespace lsdem
