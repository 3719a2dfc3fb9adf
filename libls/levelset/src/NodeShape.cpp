#include "lsdem/ls/NodeShape.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/PointHashGrid.h"
#include "lsdem/ls/GrainAsset.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/ls/LevelSetSampler.h"


#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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

/// The nodes near each node: a hash grid of cells as wide as the search radius, which is
/// three times the largest node's equal-area disk (a Voronoi neighbour of a node is rarely
/// farther than two spacings).
class NodeNeighbours
{
public:
    explicit NodeNeighbours(const SurfaceNodes& nodes)
        : mPositions(nodes.positions), mRadius(searchRadius(nodes)), mGrid(nodes.positions, mRadius)
    {
    }

    /// Every node within this distance of a node is among those around() visits.
    double radius() const { return mRadius; }

    /// Call @a visit(j) for every other node j in the 27 cells around node @a i.
    template <typename Visit>
    void around(int i, Visit&& visit) const
    {
        mGrid.around(mGrid.cellOf(mPositions[static_cast<size_t>(i)]), [&](int j) {
            if (j != i) visit(j);
        });
    }

private:
    static double searchRadius(const SurfaceNodes& nodes)
    {
        double largest = 0.0;
        for (const double a : nodes.areas) largest = std::max(largest, a);
        return std::max(3.0 * std::sqrt(largest / kPi), 1e-300);
    }

    const std::vector<Vec3>& mPositions;
    double mRadius;
    PointHashGrid mGrid;
};

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
    const auto [k11, k12, k22] = sampler.tangentialHessian(x, s.tangent, s.secondTangent(), h);
    s.k11 = k11;
    s.k12 = k12;
    s.k22 = k22;
}

/// The surface through node @a i fitted to its neighbours on the same sheet: in the frame
/// (t₁, t₂, m) of @a s, their heights w over the tangent plane by the jet
/// w = a·u₁ + b·u₂ − ½(k11·u₁² + 2·k12·u₁u₂ + k22·u₂²), least squares through the node itself;
/// then the normal turned by (a, b) and the jet fitted again in the turned frame. Why: the
/// nodes lie on the surface, and a fit over a dozen of them is good to O((ρ/R)²), where the
/// level set's voxels give curvatures wrong by O(1/R) node by node (its trilinear gradient
/// jumps across cell faces) and normals by O(h/R). Neighbours within @a radius whose first
/// normals are within 40° of this one's (so a box's other face or a plate's far side stays
/// out). Returns false, leaving @a s as it was, where fewer than 7 neighbours qualify or they
/// do not fix a jet (all on a line, or the turn beyond 40°).
bool shapeFromNeighbours(const SurfaceNodes& nodes, const std::vector<NodeShape>& first,
                         const NodeNeighbours& neighbours, int i, double radius, NodeShape& s)
{
    constexpr double kSameSheet = 0.766;  // cos 40°
    constexpr int kFewest = 7, kNearest = 12;
    const Vec3& x = nodes.positions[static_cast<size_t>(i)];
    const Vec3 m0 = first[static_cast<size_t>(i)].normal;
    std::vector<Vec3> offsets;
    neighbours.around(i, [&](int j) {
        const Vec3 q = nodes.positions[static_cast<size_t>(j)] - x;
        if (q.squaredNorm() <= radius * radius &&
            first[static_cast<size_t>(j)].normal.dot(m0) >= kSameSheet)
            offsets.push_back(q);
    });
    if (static_cast<int>(offsets.size()) < kFewest) return false;
    if (offsets.size() > static_cast<size_t>(kNearest)) {
        std::nth_element(offsets.begin(), offsets.begin() + kNearest, offsets.end(),
                         [](const Vec3& p, const Vec3& q) { return p.squaredNorm() < q.squaredNorm(); });
        offsets.resize(static_cast<size_t>(kNearest));
    }
    NodeShape fitted = s;
    fitted.normal = m0;
    fitted.tangent = anyTangent(m0);
    Eigen::Matrix<double, 5, 1> jet;
    for (int pass = 0; pass < 2; ++pass) {
        const Vec3 t2 = fitted.secondTangent();
        Eigen::MatrixXd design(offsets.size(), 5);
        Eigen::VectorXd heights(offsets.size());
        for (size_t r = 0; r < offsets.size(); ++r) {
            const double u1 = offsets[r].dot(fitted.tangent), u2 = offsets[r].dot(t2);
            design.row(static_cast<Eigen::Index>(r)) << u1, u2, -0.5 * u1 * u1, -u1 * u2,
                -0.5 * u2 * u2;
            heights[static_cast<Eigen::Index>(r)] = offsets[r].dot(fitted.normal);
        }
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
        if (qr.rank() < 5) return false;
        jet = qr.solve(heights);
        if (pass == 0) {
            const Vec3 turned = fitted.normal - jet[0] * fitted.tangent - jet[1] * t2;
            fitted.normal = turned.normalized();
            if (fitted.normal.dot(m0) < kSameSheet) return false;
            fitted.tangent = anyTangent(fitted.normal);
        }
    }
    fitted.k11 = jet[2];
    fitted.k12 = jet[3];
    fitted.k22 = jet[4];
    s = fitted;
    return true;
}

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
    const std::vector<NodeShape> fromLevelSet = shapes;
    // An exact distance gives the exact shape; voxels give the nodes' fit a better one.
    const bool exactDistance = asset.levelSet && asset.levelSet->exact;
    for (size_t i = 0; i < shapes.size() && !exactDistance; ++i)
        shapeFromNeighbours(asset.nodes, fromLevelSet, neighbours, static_cast<int>(i),
                            neighbours.radius(), shapes[i]);
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
