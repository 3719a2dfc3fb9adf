#include "lsdem/ls/NodeShape.h"

#include "lsdem/core/Constants.h"
#include "lsdem/ls/GrainAsset.h"
#include "lsdem/ls/LevelSetSampler.h"

#include "NodeHashGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace lsdem {

double patchRayAngle(int k) { return (k + 0.5) * 2.0 * kPi / kPatchRays; }

namespace {

/// The smaller principal curvature at a node.
double lowestCurvature(const NodeShape& s)
{
    const double mean = 0.5 * (s.k11 + s.k22), half = 0.5 * (s.k11 - s.k22);
    return mean - std::sqrt(half * half + s.k12 * s.k12);
}

/// A unit vector ⊥ @a m, from the axis least aligned with it (so never degenerate).
Vec3 anyTangent(const Vec3& m)
{
    Eigen::Index axis = 0;
    m.cwiseAbs().minCoeff(&axis);
    const Vec3 t = m.cross(Vec3::Unit(axis));
    return t.normalized();
}

/// Normal, tangent and shape operator of the node at @a x from the level set.
void shapeFromLevelSet(LevelSetSampler& sampler, double h, const Vec3& x, NodeShape& s)
{
    const Vec3 gradient = sampler.sample(x).gradient;
    const double length = gradient.norm();
    if (!(length > 0.0)) {
        s.normal = x.norm() > 0.0 ? Vec3(x.normalized()) : Vec3::UnitZ();
        s.tangent = anyTangent(s.normal);
        return;  // flat: no curvature known
    }
    s.normal = gradient / length;
    s.tangent = anyTangent(s.normal);
    const Vec3 t2 = s.secondTangent();
    // ∇φ's change along each tangent: the Hessian's columns H·t (central differences).
    auto change = [&](const Vec3& t) {
        return Vec3((sampler.sample(x + h * t).gradient - sampler.sample(x - h * t).gradient) /
                    (2.0 * h));
    };
    const Vec3 along1 = change(s.tangent), along2 = change(t2);
    s.k11 = s.tangent.dot(along1);
    s.k22 = t2.dot(along2);
    s.k12 = 0.5 * (t2.dot(along1) + s.tangent.dot(along2));
}

/// The nodes near each node: a hash grid of cells as wide as the search radius, which is
/// three times the largest node's equal-area disk (a Voronoi neighbour of a node is rarely
/// farther than two spacings).
class NodeNeighbours
{
public:
    explicit NodeNeighbours(const SurfaceNodes& nodes)
        : mPositions(nodes.positions), mGrid(nodes.positions, searchRadius(nodes))
    {
    }

    /// Call @a visit(j) for every other node j in the 27 cells around node @a i.
    template <typename Visit>
    void around(int i, Visit&& visit) const
    {
        const Eigen::Vector3i c = mGrid.cellOf(mPositions[static_cast<size_t>(i)]);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::vector<int>* inCell = mGrid.nodesIn(c + Eigen::Vector3i(dx, dy, dz));
                    if (!inCell) continue;
                    for (const int j : *inCell)
                        if (j != i) visit(j);
                }
    }

private:
    static double searchRadius(const SurfaceNodes& nodes)
    {
        double largest = 0.0;
        for (const double a : nodes.areas) largest = std::max(largest, a);
        return std::max(3.0 * std::sqrt(largest / kPi), 1e-300);
    }

    const std::vector<Vec3>& mPositions;
    NodeHashGrid mGrid;
};

/// A convex polygon in a node's tangent plane (u₁, u₂), cut by half-planes.
class PlanePolygon
{
public:
    /// The regular polygon of @a corners corners inscribed in the circle of radius @a radius.
    PlanePolygon(double radius, int corners)
    {
        for (int k = 0; k < corners; ++k) {
            const double angle = 2.0 * kPi * k / corners;
            mCorners.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
        }
    }
    /// Keep the part where u·q ≤ @a limit.
    void keepBelow(const Eigen::Vector2d& q, double limit)
    {
        std::vector<Eigen::Vector2d> kept;
        const size_t n = mCorners.size();
        for (size_t k = 0; k < n; ++k) {
            const Eigen::Vector2d& a = mCorners[k];
            const Eigen::Vector2d& b = mCorners[(k + 1) % n];
            const double da = a.dot(q) - limit, db = b.dot(q) - limit;
            if (da <= 0.0) kept.push_back(a);
            if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
                kept.push_back(a + (da / (da - db)) * (b - a));
        }
        mCorners.swap(kept);
    }
    double area() const
    {
        double twice = 0.0;
        const size_t n = mCorners.size();
        for (size_t k = 0; k < n; ++k) {
            const Eigen::Vector2d& a = mCorners[k];
            const Eigen::Vector2d& b = mCorners[(k + 1) % n];
            twice += a.x() * b.y() - a.y() * b.x();
        }
        return 0.5 * twice;
    }

private:
    std::vector<Eigen::Vector2d> mCorners;
};

/// Node @a i's Voronoi cell in its tangent plane, along each ray: the nearest bisector of the
/// node and a neighbour (projected on the plane) that the ray meets.
void cellOfNode(const SurfaceNodes& nodes, const std::vector<NodeShape>& shapes,
                const NodeNeighbours& neighbours, int i, NodeShape& s)
{
    const Vec3& x = nodes.positions[static_cast<size_t>(i)];
    const double disk = std::sqrt(nodes.areas[static_cast<size_t>(i)] / kPi);
    const double cap = 2.0 * disk;
    std::array<double, kPatchRays> extent;
    extent.fill(cap);
    std::array<double, kPatchRays> cs, sn;
    for (int k = 0; k < kPatchRays; ++k) {
        cs[static_cast<size_t>(k)] = std::cos(patchRayAngle(k));
        sn[static_cast<size_t>(k)] = std::sin(patchRayAngle(k));
    }
    const Vec3 t2 = s.secondTangent();
    // The cell itself, for its area: the cap's circle as a 64-gon, cut by the same bisectors.
    PlanePolygon polygon(cap, 64);
    neighbours.around(i, [&](int j) {
        if (shapes[static_cast<size_t>(j)].normal.dot(s.normal) <= 0.0) return;  // the far side
        const Vec3 q = nodes.positions[static_cast<size_t>(j)] - x;
        const double q1 = q.dot(s.tangent), q2 = q.dot(t2);
        const double half = 0.5 * (q1 * q1 + q2 * q2);
        if (!(half > 0.0)) return;
        polygon.keepBelow(Eigen::Vector2d(q1, q2), half);
        for (size_t k = 0; k < extent.size(); ++k) {
            const double along = q1 * cs[k] + q2 * sn[k];
            if (along > 0.0) extent[k] = std::min(extent[k], half / along);
        }
    });
    // Scaled so that the rays' rule (Σ ½e²·Δθ) measures the cell's own area: the rule cuts a
    // cell's corners or overshoots them (a square's area −2.4 % with a ray along a side,
    // +4.9 % turned by half a ray spacing), and then the cells would not tile.
    double rays = 0.0;
    for (const double e : extent) rays += 0.5 * e * e * (2.0 * kPi / kPatchRays);
    const double area = polygon.area();
    const double scale = rays > 0.0 && area > 0.0 ? std::sqrt(area / rays) : 1.0;
    s.reach = 0.0f;
    for (size_t k = 0; k < extent.size(); ++k) {
        s.extents[k] = static_cast<float>(scale * extent[k]);
        s.reach = std::max(s.reach, s.extents[k]);
    }
}

} // namespace

std::vector<NodeShape> nodeShapesOf(const GrainAsset& asset)
{
    std::vector<NodeShape> shapes(asset.nodes.size());
    LevelSetSampler sampler(*asset.levelSet);
    for (size_t i = 0; i < shapes.size(); ++i)
        shapeFromLevelSet(sampler, asset.voxelSize, asset.nodes.positions[i], shapes[i]);
    const NodeNeighbours neighbours(asset.nodes);
    for (size_t i = 0; i < shapes.size(); ++i) {
        NodeShape& s = shapes[i];
        cellOfNode(asset.nodes, shapes, neighbours, static_cast<int>(i), s);
        const double e = s.reach;
        // Rounded up: a bound must not shrink in the float.
        s.lift = std::nextafter(static_cast<float>(0.5 * e * e * std::max(0.0, -lowestCurvature(s))),
                                std::numeric_limits<float>::max());
    }
    return shapes;
}

double patchReachOf(const std::vector<NodeShape>& shapes)
{
    double reach = 0.0;
    for (const NodeShape& s : shapes) reach = std::max(reach, double(s.reach) + double(s.lift));
    return reach;
}

double concavityOf(const std::vector<NodeShape>& shapes)
{
    double concavity = 0.0;
    for (const NodeShape& s : shapes) concavity = std::max(concavity, -lowestCurvature(s));
    return concavity;
}

GrainAsset withNodeShapes(const GrainAsset& asset)
{
    GrainAsset out = asset;
    out.nodeShapes = nodeShapesOf(asset);
    out.patchReach = patchReachOf(out.nodeShapes);
    out.patchConcavity = concavityOf(out.nodeShapes);
    return out;
}

} // namespace lsdem
