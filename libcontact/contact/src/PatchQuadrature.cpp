#include "lsdem/contact/PatchQuadrature.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace lsdem {

std::string nodeQuadratureName(NodeQuadrature q)
{
    return q == NodeQuadrature::Point ? "node" : "patch";
}

NodeQuadrature parseNodeQuadrature(const std::string& name)
{
    if (name == "node") return NodeQuadrature::Point;
    if (name == "patch") return NodeQuadrature::Patch;
    throw Error("", "unknown quadrature '" + name + "'", "use node or patch");
}

double patchRadius(double area) { return std::sqrt(area / kPi); }

namespace {

/// The rays' directions, cos and sin of patchRayAngle(k).
struct Rays
{
    std::array<double, kPatchRays> cos{}, sin{};
    Rays()
    {
        for (int k = 0; k < kPatchRays; ++k) {
            cos[static_cast<size_t>(k)] = std::cos(patchRayAngle(k));
            sin[static_cast<size_t>(k)] = std::sin(patchRayAngle(k));
        }
    }
};

const Rays& rays()
{
    static const Rays r;
    return r;
}

/// The smallest and largest eigenvalues of [[c11, c12], [c12, c22]].
std::pair<double, double> eigenRange(double c11, double c12, double c22)
{
    const double mean = 0.5 * (c11 + c22), half = 0.5 * (c11 - c22);
    const double spread = std::sqrt(half * half + c12 * c12);
    return {mean - spread, mean + spread};
}

/// The antiderivatives along a ray of d(r) = d0 + a·r + b·r², with the area element r dr:
/// of r, d·r, d·r² and d²·r, at r.
struct RayIntegrals
{
    double area, depth, moment, squareDepth;
};

RayIntegrals rayIntegralsAt(double d0, double a, double b, double r)
{
    const double r2 = r * r, r3 = r2 * r, r4 = r3 * r, r5 = r4 * r, r6 = r5 * r;
    return {0.5 * r2, d0 * r2 / 2 + a * r3 / 3 + b * r4 / 4, d0 * r3 / 3 + a * r4 / 4 + b * r5 / 5,
            d0 * d0 * r2 / 2 + 2 * d0 * a * r3 / 3 + (a * a + 2 * d0 * b) * r4 / 4 +
                2 * a * b * r5 / 5 + b * b * r6 / 6};
}

/// The integrals over the patch that reaches extentOf(k) along ray k: exact along each ray
/// (d⁺ is a polynomial between its roots), the trapezoid rule over the rays' angles.
template <typename ExtentOf>
PatchIntegral integrateRays(const PatchDepth& d, ExtentOf extentOf)
{
    PatchIntegral out;
    const Rays& r = rays();
    const double weight = 2.0 * kPi / kPatchRays;
    for (size_t k = 0; k < static_cast<size_t>(kPatchRays); ++k) {
        const double rho = extentOf(k);
        const double cs = r.cos[k], sn = r.sin[k];
        const double a = d.g1 * cs + d.g2 * sn;
        const double b = -0.5 * (d.c11 * cs * cs + 2 * d.c12 * cs * sn + d.c22 * sn * sn);
        // The deepest point along the ray: an end, or the vertex of a concave d. A ray that
        // never goes in adds nothing (most of a patch at a contact's edge).
        double peak = std::max(d.d0, d.d0 + rho * (a + rho * b));
        if (b < 0.0) {
            const double vertex = -a / (2 * b);
            if (vertex > 0.0 && vertex < rho)
                peak = std::max(peak, d.d0 + vertex * (a + vertex * b));
        }
        if (!(peak > 0.0)) continue;
        out.peak = std::max(out.peak, peak);
        // d along the ray is positive between its roots in (0, ρ) and the ends.
        std::array<double, 4> cuts{0.0, rho, rho, rho};
        int count = 1;
        const double disc = a * a - 4 * b * d.d0;
        if (disc >= 0.0) {
            const double q = -0.5 * (a + std::copysign(std::sqrt(disc), a));
            if (q != 0.0) {
                const double root = d.d0 / q;
                if (root > 0.0 && root < rho) cuts[static_cast<size_t>(count++)] = root;
                if (b != 0.0) {
                    const double other = q / b;
                    if (other > 0.0 && other < rho) cuts[static_cast<size_t>(count++)] = other;
                }
            }
        }
        if (count == 3 && cuts[1] > cuts[2]) std::swap(cuts[1], cuts[2]);
        cuts[static_cast<size_t>(count)] = rho;
        RayIntegrals ray{0, 0, 0, 0};
        for (int p = 0; p < count; ++p) {
            const double lo = cuts[static_cast<size_t>(p)], hi = cuts[static_cast<size_t>(p + 1)];
            if (!(hi > lo)) continue;
            const double mid = 0.5 * (lo + hi);
            if (!(d.d0 + mid * (a + mid * b) > 0.0)) continue;
            const RayIntegrals upper = rayIntegralsAt(d.d0, a, b, hi);
            const RayIntegrals lower = rayIntegralsAt(d.d0, a, b, lo);
            ray.area += upper.area - lower.area;
            ray.depth += upper.depth - lower.depth;
            ray.moment += upper.moment - lower.moment;
            ray.squareDepth += upper.squareDepth - lower.squareDepth;
        }
        out.area += weight * ray.area;
        out.depth += weight * ray.depth;
        out.squareDepth += weight * ray.squareDepth;
        out.moment1 += weight * ray.moment * cs;
        out.moment2 += weight * ray.moment * sn;
    }
    return out;
}

} // namespace

double patchPeakBound(const PatchDepth& d, double radius)
{
    const double slope2 = d.g1 * d.g1 + d.g2 * d.g2, slope = std::sqrt(slope2);
    const double lowest = eigenRange(d.c11, d.c12, d.c22).first;
    const double rim = d.d0 + slope * radius + 0.5 * radius * radius * std::max(0.0, -lowest);
    // A patch bending away from the body everywhere (C positive definite) peaks at most at
    // the vertex of d0 + |g|·r − ½·λ_min·r², which is far lower for a tilted patch of a curved
    // contact (most nodes near it, which so need no integral).
    return lowest > 0.0 ? std::min(rim, d.d0 + 0.5 * slope2 / lowest) : rim;
}

PatchIntegral integratePatch(const PatchDepth& d, double radius)
{
    const double rho = radius, rho2 = rho * rho;
    const double slope = std::sqrt(d.g1 * d.g1 + d.g2 * d.g2);
    const double highest = eigenRange(d.c11, d.c12, d.c22).second;
    if (patchPeakBound(d, radius) <= 0.0) return {};  // wholly clear
    if (!(d.d0 - slope * rho - 0.5 * rho2 * std::max(0.0, highest) > 0.0))
        return integrateRays(d, [rho](size_t) { return rho; });
    // Wholly in contact: the integrals of the quadratic over the disk in closed form (the
    // rays' rule gives the same, being exact for it), the peak from the rays' ends.
    PatchIntegral out = integrateRays(d, [rho](size_t) { return rho; });
    const double disk = kPi * rho2, trace = d.c11 + d.c22;
    const double squares =
        3 * d.c11 * d.c11 + 3 * d.c22 * d.c22 + 2 * d.c11 * d.c22 + 4 * d.c12 * d.c12;
    out.area = disk;
    out.depth = disk * (d.d0 - trace * rho2 / 8);
    out.moment1 = disk * rho2 / 4 * d.g1;
    out.moment2 = disk * rho2 / 4 * d.g2;
    out.squareDepth = disk * d.d0 * d.d0 + disk * rho2 / 4 * (slope * slope - d.d0 * trace) +
                      kPi * rho2 * rho2 * rho2 * squares / 96;
    return out;
}

PatchIntegral integratePatch(const PatchDepth& d, const std::array<float, kPatchRays>& extents,
                             double reach)
{
    if (patchPeakBound(d, reach) <= 0.0) return {};
    return integrateRays(d, [&extents](size_t k) { return double(extents[k]); });
}

PatchFrame patchFrame(const NodeShape& shape, const Eigen::Matrix3d& rotation)
{
    PatchFrame frame;
    frame.normal = rotation * shape.normal;
    frame.tangent1 = rotation * shape.tangent;
    frame.tangent2 = frame.normal.cross(frame.tangent1);
    frame.k11 = shape.k11;
    frame.k12 = shape.k12;
    frame.k22 = shape.k22;
    return frame;
}

PatchDepth patchDepth(const PatchFrame& frame, double phi, const Vec3& gradient, double h11,
                      double h12, double h22)
{
    PatchDepth d;
    d.d0 = -phi;
    d.g1 = -gradient.dot(frame.tangent1);
    d.g2 = -gradient.dot(frame.tangent2);
    const double facing = -gradient.dot(frame.normal);
    d.c11 = facing * frame.k11 + h11;
    d.c12 = facing * frame.k12 + h12;
    d.c22 = facing * frame.k22 + h22;
    return d;
}

bool fillPatchContact(const PatchIntegral& integral, const PatchFrame& frame,
                      NodeContact& contact, Vec3& offset)
{
    if (!(integral.area > 0.0) || !(integral.depth > 0.0)) return false;
    contact.area = integral.area;
    contact.depth = integral.depth / integral.area;
    contact.squareDepth = integral.squareDepth / integral.area;
    // (Never 0 for a patch in contact: it marks the contact as a patch's.)
    contact.peakDepth = std::max(static_cast<float>(std::max(integral.peak, contact.depth)),
                                 std::numeric_limits<float>::min());
    offset = (integral.moment1 / integral.depth) * frame.tangent1 +
             (integral.moment2 / integral.depth) * frame.tangent2;
    return true;
}

void addPatchContact(int node, const NodeShape& shape, const PatchFrame& frame,
                     const PatchDepth& depth, const Vec3& nodePosition, const Vec3& normal,
                     std::vector<NodeContact>& out, long long& inContact)
{
    if (patchPeakBound(depth, shape.reach) <= 0.0) return;
    NodeContact c;
    Vec3 offset;
    if (!fillPatchContact(integratePatch(depth, shape.extents, shape.reach), frame, c, offset))
        return;
    ++inContact;
    c.node = node;
    c.normal = normal;
    c.point = nodePosition + offset + 0.5 * c.depth * normal;
    out.push_back(c);
}

} // namespace lsdem
