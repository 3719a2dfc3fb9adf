// Node shapes (NodeShape.h): each node's normal, tangent frame and shape operator from the level
// set (sampled exactly) and from the nodes (an asset of voxels), against a sphere's and a box's
// exact geometry; each
// node's patch, its Voronoi cell in its tangent plane along the rays, against a brute-force
// search over every node; the patches' reach; withNodeShapes; and a node without a gradient.
#include "lsdem/ls/NodeShape.h"

#include "lsdem/core/Constants.h"
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/ExactDistance.h"
#include "lsdem/ls/GrainAsset.h"
#include "lsdem/ls/LevelSetGrid.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

using namespace lsdem;

namespace {

constexpr double kRadius = 1.0;  // the sphere
constexpr double kVoxel = 0.1;

GrainAsset bakeSphere()
{
    BakeOptions o;
    o.voxelSize = kVoxel;
    o.nodeSpacing = 0.3;  // ~160 nodes
    std::vector<std::string> warnings;
    return bakeAnalytic(AnalyticShape::sphere(kRadius), o, warnings);
}

/// A 2 × 1.6 × 1.2 box: structured face grids of spacing 0.2.
const AnalyticShape& boxShape()
{
    static const AnalyticShape box = AnalyticShape::box(2.0, 1.6, 1.2);
    return box;
}

GrainAsset bakeBox()
{
    BakeOptions o;
    o.voxelSize = kVoxel;
    o.nodeSpacing = 0.2;
    std::vector<std::string> warnings;
    return bakeAnalytic(boxShape(), o, warnings);
}

/// A sphere's distance with its gradient in closed form, x/|x| (or −x/|x| for the space outside
/// it, a spherical cavity, @a inverted): unlike AnalyticShape's (x − closest point)/φ, well
/// conditioned at the surface.
class RadialDistance final : public ExactDistance
{
public:
    RadialDistance(double radius, bool inverted) : mRadius(radius), mSign(inverted ? -1.0 : 1.0) {}
    double phi(const Vec3& p) const override { return mSign * (p.norm() - mRadius); }
    Vec3 gradient(const Vec3& p) const override { return mSign * p.normalized(); }

private:
    double mRadius, mSign;
};

/// @a asset with its level set sampled as @a distance.
GrainAsset sampledAs(GrainAsset asset, std::shared_ptr<const ExactDistance> distance)
{
    auto levelSet = std::make_shared<LevelSetGrid>(*asset.levelSet);
    levelSet->exact = std::move(distance);
    asset.levelSet = levelSet;
    return asset;
}

/// For a node of the box: the axis of its face, and its distance within that face to the
/// face's nearest edge (negative if it is on no face alone: an edge or a corner).
std::pair<int, double> faceOf(const Vec3& p)
{
    const Vec3 h = boxShape().halfExtents();
    int axis = -1;
    for (int a = 0; a < 3; ++a)
        if (std::abs(std::abs(p[a]) - h[a]) < 1e-9) {
            if (axis >= 0) return {-1, -1.0};  // on two faces
            axis = a;
        }
    if (axis < 0) return {-1, -1.0};
    double edge = HUGE_VAL;
    for (int a = 0; a < 3; ++a)
        if (a != axis) edge = std::min(edge, h[a] - std::abs(p[a]));
    return {axis, edge};
}

} // namespace

// A sphere of radius R sampled as its exact distance: ∇φ = x/|x|, so the normal is radial and
// the frame orthonormal to round-off. The curvatures are the central differences of ∇φ one
// voxel h apart along a tangent t: ((x + ht) − (x − ht))/(2h·√(R² + h²)) = t/√(R² + h²), so
// k11 = k22 = 1/√(R² + h²) and k12 = 0, exactly but for round-off (the gradient of an exact
// distance is (x − closest)/φ, φ ≈ h²/2R here: 1e-9 covers it), which is 1/R to within
// h²/(2R²) = 0.5 %. (At the node itself φ is 0 or an ulp, the nodes being projected on the
// surface: the normal there must not depend on which.)
TEST(NodeShape, SphereWithItsExactDistanceIsRoundWithCurvatureOneOverR)
{
    const GrainAsset a = withExactDistance(bakeSphere(), AnalyticShape::sphere(kRadius).exactDistance());
    const std::vector<NodeShape> shapes = nodeShapesOf(a);
    ASSERT_EQ(shapes.size(), a.nodes.size());
    ASSERT_GT(shapes.size(), 100u);
    // The worst node of each kind, and how many nodes miss (one line each on failure).
    double worstNormal = 0.0, worstCentral = 0.0, worstRadius = 0.0;
    size_t worstNode = 0, badNormals = 0;
    for (size_t i = 0; i < shapes.size(); ++i) {
        const NodeShape& s = shapes[i];
        const Vec3& x = a.nodes.positions[i];
        EXPECT_NEAR(s.tangent.norm(), 1.0, 1e-14);
        EXPECT_NEAR(s.tangent.dot(s.normal), 0.0, 1e-14);
        EXPECT_NEAR(s.normal.norm(), 1.0, 1e-14);
        const double normalError = (s.normal - x.normalized()).norm();
        const double central = 1.0 / std::sqrt(x.squaredNorm() + kVoxel * kVoxel);
        if (normalError > worstNormal) worstNode = i;
        badNormals += normalError > 1e-12;
        worstNormal = std::max(worstNormal, normalError);
        worstCentral = std::max({worstCentral, std::abs(s.k11 - central), std::abs(s.k22 - central),
                                 std::abs(s.k12)});
        worstRadius = std::max({worstRadius, std::abs(s.k11 * kRadius - 1.0),
                                std::abs(s.k22 * kRadius - 1.0)});
    }
    const Vec3& x = a.nodes.positions[worstNode];
    EXPECT_EQ(badNormals, 0u) << "of " << shapes.size() << " nodes";
    EXPECT_LT(worstNormal, 1e-12) << "node " << worstNode << " at (" << x.transpose()
                                  << "), φ there " << AnalyticShape::sphere(kRadius).signedDistance(x)
                                  << ", normal (" << shapes[worstNode].normal.transpose() << ")";
    EXPECT_LT(worstCentral * kRadius, 1e-9);
    EXPECT_LT(worstRadius, 0.6 * kVoxel * kVoxel / (kRadius * kRadius));
}

// The same, with the sphere's gradient taken as x/|x| (RadialDistance): what nodeShapesOf makes
// of a well-conditioned exact gradient. The same tolerances: the normal radial to round-off,
// k11 = k22 = 1/√(R² + h²), k12 = 0 (the gradients it differences are now exact to an ulp,
// so 1e-12). If this passes and the test above fails, the fault is in the exact distance's
// gradient at the nodes, not in nodeShapesOf's arithmetic.
TEST(NodeShape, SphereWithAWellConditionedGradientIsRoundWithCurvatureOneOverR)
{
    const GrainAsset a = sampledAs(bakeSphere(), std::make_shared<RadialDistance>(kRadius, false));
    const std::vector<NodeShape> shapes = nodeShapesOf(a);
    ASSERT_EQ(shapes.size(), a.nodes.size());
    double worstNormal = 0.0, worstCentral = 0.0;
    for (size_t i = 0; i < shapes.size(); ++i) {
        const NodeShape& s = shapes[i];
        const Vec3& x = a.nodes.positions[i];
        const double central = 1.0 / std::sqrt(x.squaredNorm() + kVoxel * kVoxel);
        worstNormal = std::max(worstNormal, (s.normal - x.normalized()).norm());
        worstCentral = std::max({worstCentral, std::abs(s.k11 - central), std::abs(s.k22 - central),
                                 std::abs(s.k12)});
        EXPECT_NEAR(s.tangent.norm(), 1.0, 1e-14);
        EXPECT_NEAR(s.tangent.dot(s.normal), 0.0, 1e-14);
        EXPECT_NEAR(s.k11 * kRadius, 1.0, 0.6 * kVoxel * kVoxel / (kRadius * kRadius)) << i;
    }
    EXPECT_LT(worstNormal, 1e-12);
    EXPECT_LT(worstCentral * kRadius, 1e-12);
}

// The same sphere from its voxels. The voxels' own shape is poor node by node (∇ of the
// trilinear interpolant jumps across cell faces: differenced a voxel apart, each k errs by
// O(1/R) whatever h, measured RMS 0.13), so the shape comes from the nodes, which lie on the
// sphere: a jet fitted to the node's 12 nearest neighbours. On a sphere a neighbour at
// tangential distance u stands w(u) = R − √(R² − u²) = u²/2R·f(u/R) below the tangent plane,
// f(x) = 2(1 − √(1 − x²))/x² ≥ 1, so the fitted k·R is a weighted mean of f over the
// neighbours: in [1, f(ρ/R)], ρ the farthest of them (+6 % at the 160 nodes of spacing 0.3
// and ρ up to 0.6; +0.6 % at spacing 0.1). The fit's other terms absorb a little (measured
// below 1e-3 at both), hence 1e-3 of slack either side. The normal: radial but for the tilt
// those residuals fit, (f(ρ/R) − 1)·ρ/2R (their size over their reach) times the least
// squares' leverage on an uneven neighbourhood (measured up to 1.25; 2 allowed): a third of a
// degree at most here, where the voxels' gradient errs by up to 4 degrees.
TEST(NodeShape, SphereFromItsVoxelsTakesItsShapeFromTheNodes)
{
    const auto f = [](double x) { return 2.0 * (1.0 - std::sqrt(1.0 - x * x)) / (x * x); };
    for (const double spacing : {0.3, 0.1}) {
        BakeOptions o;
        o.voxelSize = kVoxel;
        o.nodeSpacing = spacing;
        std::vector<std::string> warnings;
        const GrainAsset a = bakeAnalytic(AnalyticShape::sphere(kRadius), o, warnings);
        const std::vector<NodeShape> shapes = nodeShapesOf(a);
        ASSERT_EQ(shapes.size(), a.nodes.size());
        for (size_t i = 0; i < shapes.size(); ++i) {
            const NodeShape& s = shapes[i];
            const Vec3& x = a.nodes.positions[i];
            std::vector<double> distances;
            for (const Vec3& y : a.nodes.positions)
                if (y.dot(x) > 0.0 && &y != &x) distances.push_back((y - x).norm());
            std::nth_element(distances.begin(), distances.begin() + 11, distances.end());
            const double rho = *std::max_element(distances.begin(), distances.begin() + 12);
            const double highest = f(rho / kRadius);
            EXPECT_LT((s.normal - x.normalized()).norm(), 2.0 * (highest - 1.0) * rho / (2 * kRadius))
                << spacing << " " << i;
            EXPECT_NEAR(s.tangent.norm(), 1.0, 1e-14);
            EXPECT_NEAR(s.tangent.dot(s.normal), 0.0, 1e-14);
            // The principal curvatures: both in [1, f(ρ/R)]/R.
            const double mean = 0.5 * (s.k11 + s.k22), half = 0.5 * (s.k11 - s.k22);
            const double spread = std::sqrt(half * half + s.k12 * s.k12);
            for (const double k : {mean - spread, mean + spread}) {
                EXPECT_GE(k * kRadius, 1.0 - 1e-3) << spacing << " " << i;
                EXPECT_LE(k * kRadius, highest + 1e-3) << spacing << " " << i;
            }
        }
    }
}

// A box's faces are flat: a node on a face farther than a voxel from its edges (the central
// differences reach a voxel along the face) has the face's normal and no curvature. With the
// exact distance, exactly (the gradient of a face's distance is its normal, its change along
// the face nil). From the voxels: a linear φ is reproduced exactly by trilinear interpolation,
// so what is left is the storage's rounding, within 2^-21 of a brick's largest |φ| (≤ 7h near
// the surface): ∇φ errs by ≤ 2·7h·2^-21/h ≈ 7e-6 and its difference over 2h by ≤ 7e-6/h; the
// interpolation reads corners up to a voxel farther, so those nodes are taken 3h from the edges.
TEST(NodeShape, BoxFacesAreFlatAwayFromTheEdges)
{
    for (const bool exact : {true, false}) {
        const GrainAsset voxels = bakeBox();
        const GrainAsset a = exact ? withExactDistance(voxels, boxShape().exactDistance()) : voxels;
        const std::vector<NodeShape> shapes = nodeShapesOf(a);
        ASSERT_EQ(shapes.size(), a.nodes.size());
        const double margin = exact ? 1.0001 * kVoxel : 3.0 * kVoxel;
        const double normalTolerance = exact ? 1e-14 : 1e-5;
        const double curvatureTolerance = exact ? 1e-12 : 7e-6 / kVoxel;
        int faceNodes = 0;
        for (size_t i = 0; i < shapes.size(); ++i) {
            const Vec3& p = a.nodes.positions[i];
            const auto [axis, edge] = faceOf(p);
            if (axis < 0 || edge < margin) continue;
            ++faceNodes;
            const NodeShape& s = shapes[i];
            Vec3 normal = Vec3::Zero();
            normal[axis] = p[axis] > 0.0 ? 1.0 : -1.0;
            EXPECT_LT((s.normal - normal).norm(), normalTolerance) << (exact ? "exact " : "voxels ") << i;
            EXPECT_NEAR(s.tangent.dot(s.normal), 0.0, 1e-14);
            EXPECT_NEAR(s.k11, 0.0, curvatureTolerance) << (exact ? "exact " : "voxels ") << i;
            EXPECT_NEAR(s.k12, 0.0, curvatureTolerance) << (exact ? "exact " : "voxels ") << i;
            EXPECT_NEAR(s.k22, 0.0, curvatureTolerance) << (exact ? "exact " : "voxels ") << i;
        }
        EXPECT_GT(faceNodes, 60) << exact;
    }
}

// The rays along which a patch is described: (k + ½)·2π/kPatchRays from t₁.
TEST(NodeShape, RaysAreEvenlySpacedAndOffsetByHalfASpacing)
{
    for (int k = 0; k < kPatchRays; ++k)
        EXPECT_NEAR(patchRayAngle(k), (k + 0.5) * 2.0 * kPi / kPatchRays, 1e-15);
}

// Each node's patch has the shape of its Voronoi cell in its tangent plane: along ray k the cell
// reaches the nearest bisector (in the plane) between the node and any other node whose normal
// is less than 90° from its own, and never beyond twice the radius of the disk of its area.
// The extents are then scaled so that the rays' rule (Σ ½e²·Δθ) gives the cell's own area.
// Here the cell is found by a search over every node (not only the near ones the code looks
// at), along the 16 rays and along 4096 (whose rule gives the cell's area to ~1e-6). The code
// clips a polygon instead, with the cap's circle as a 64-gon: a cell the cap cuts would differ
// by up to 0.16 % of its area, but the few rays the cap stops here (cut > 10·capped) change no
// cell's area measurably. So the
// extents match the cell's times one scale, and their rule the cell's area, within 2e-6
// (measured 2.5e-7 and 4.3e-7: the floats' 6e-8 and the 4096 rays' rule).
TEST(NodeShape, PatchesHaveTheShapeAndAreaOfTheNodesVoronoiCells)
{
    for (const GrainAsset& a : {bakeSphere(), bakeBox()}) {
        const std::vector<NodeShape> shapes = nodeShapesOf(a);
        ASSERT_EQ(shapes.size(), a.nodes.size());
        int capped = 0, cut = 0;
        double worstShape = 0.0, worstArea = 0.0;
        for (size_t i = 0; i < shapes.size(); ++i) {
            const NodeShape& s = shapes[i];
            const Vec3 t1 = s.tangent, t2 = s.normal.cross(s.tangent);
            const double cap = 2.0 * std::sqrt(a.nodes.areas[i] / kPi);
            // The cell along a ray at @a angle from t₁: the point x + e·ray is nearer (in the
            // plane) to node j than to node i beyond e = |q|²/(2·q·ray), q node j's offset
            // projected on the plane.
            auto cellAlong = [&](double angle) {
                const Vec3 ray = std::cos(angle) * t1 + std::sin(angle) * t2;
                double nearest = cap;
                for (size_t j = 0; j < shapes.size(); ++j) {
                    if (j == i || shapes[j].normal.dot(s.normal) <= 0.0) continue;
                    Vec3 q = a.nodes.positions[j] - a.nodes.positions[i];
                    q -= q.dot(s.normal) * s.normal;
                    const double along = q.dot(ray);
                    if (along > 0.0 && q.squaredNorm() > 0.0)
                        nearest = std::min(nearest, 0.5 * q.squaredNorm() / along);
                }
                return nearest;
            };
            std::array<double, kPatchRays> cell;
            double cellRule = 0.0;
            for (int k = 0; k < kPatchRays; ++k) {
                cell[static_cast<size_t>(k)] = cellAlong((k + 0.5) * 2.0 * kPi / kPatchRays);
                cellRule += 0.5 * cell[static_cast<size_t>(k)] * cell[static_cast<size_t>(k)] *
                            2.0 * kPi / kPatchRays;
                (cell[static_cast<size_t>(k)] < cap ? cut : capped) += 1;
            }
            const int fine = 4096;
            double cellArea = 0.0;
            for (int k = 0; k < fine; ++k) {
                const double e = cellAlong((k + 0.5) * 2.0 * kPi / fine);
                cellArea += 0.5 * e * e * 2.0 * kPi / fine;
            }
            const double scale = std::sqrt(cellArea / cellRule);
            float largest = 0.0f;
            double area = 0.0;
            for (int k = 0; k < kPatchRays; ++k) {
                const float e = s.extents[static_cast<size_t>(k)];
                worstShape = std::max(worstShape, std::abs(double(e) / (scale * cell[static_cast<size_t>(k)]) - 1.0));
                EXPECT_GT(e, 0.0f);
                largest = std::max(largest, e);
                area += 0.5 * double(e) * double(e) * 2.0 * kPi / kPatchRays;
            }
            worstArea = std::max(worstArea, std::abs(area / cellArea - 1.0));
            EXPECT_EQ(s.reach, largest) << i;
        }
        EXPECT_LT(worstShape, 2e-6);
        EXPECT_LT(worstArea, 2e-6);
        EXPECT_GT(cut, 10 * capped);  // the neighbours close the cells
    }
}

// patchReachOf: over the nodes, the largest of e + lift, e the patch's largest extent and lift
// = ½e²·max(0, −λ_min(S)) (the bend's rise over e where the patch bends toward the body; set
// here as nodeShapesOf sets it, checked on a cavity below). Shapes made by hand, the
// eigenvalues by Eigen.
TEST(NodeShape, PatchReachOfHandMadeShapes)
{
    std::vector<NodeShape> shapes(3);
    const double ks[3][3] = {{1.0, 0.0, 2.0}, {-1.0, 0.3, 0.5}, {0.0, 0.8, 0.0}};
    const float reaches[3] = {0.3f, 0.2f, 0.25f};
    double expected = 0.0;
    for (size_t i = 0; i < 3; ++i) {
        shapes[i].k11 = ks[i][0];
        shapes[i].k12 = ks[i][1];
        shapes[i].k22 = ks[i][2];
        shapes[i].reach = reaches[i];
        shapes[i].extents.fill(reaches[i]);
        Eigen::Matrix2d S;
        S << ks[i][0], ks[i][1], ks[i][1], ks[i][2];
        const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues()(0);
        const double e = reaches[i];
        shapes[i].lift = static_cast<float>(0.5 * e * e * std::max(0.0, -lowest));
        expected = std::max(expected, e + 0.5 * e * e * std::max(0.0, -lowest));
    }
    // Node 0 is convex: 0.3; node 1 (λ_min = −0.25 − √(0.5625 + 0.09) ≈ −1.058): 0.2212;
    // node 2 (λ_min = −0.8): 0.25 + ½·0.0625·0.8 = 0.275. The largest, node 0's 0.3.
    EXPECT_NEAR(patchReachOf(shapes), expected, 1e-7);
    EXPECT_NEAR(patchReachOf(shapes), 0.3, 1e-7);  // (a float's 0.3)
    shapes[0].lift = 0.5f * 0.09f * 3.0f;  // node 0 now bends toward the body: 0.3 + ½·0.09·3
    EXPECT_NEAR(patchReachOf(shapes), 0.3 + 0.5 * 0.09 * 3.0, 1e-7);
    EXPECT_EQ(patchReachOf({}), 0.0);
}

// The patches' reach (patchReachOf, through withNodeShapes): how far beyond its node a patch
// can reach toward a body. On the convex sphere (RadialDistance, so that every node has the
// same curvature) no less than the largest patch radius √(A/π). Turned inside out (the same
// nodes on a spherical cavity: the normals flip, S = −I/√(R² + h²) at every node), each patch
// bends toward the body by ½e²/√(R² + h²) over its extent e, so the reach grows from r to
// r + ½r²/√(R² + h²) (a function of e increasing, the same at every node, so the largest at
// the same node). The box's faces are flat, its edges convex: no less than its largest radius.
TEST(NodeShape, PatchReachCoversTheLargestPatchAndItsBend)
{
    const GrainAsset sphere = bakeSphere();
    const GrainAsset convex =
        withNodeShapes(sampledAs(sphere, std::make_shared<RadialDistance>(kRadius, false)));
    const GrainAsset cavity =
        withNodeShapes(sampledAs(sphere, std::make_shared<RadialDistance>(kRadius, true)));
    double largest = 0.0;
    for (const double area : sphere.nodes.areas) largest = std::max(largest, std::sqrt(area / kPi));
    const double r = convex.patchReach, k = 1.0 / std::sqrt(kRadius * kRadius + kVoxel * kVoxel);
    EXPECT_GE(r, largest);
    for (const NodeShape& s : cavity.nodeShapes) {
        ASSERT_NEAR(s.k11, -k, 1e-12);
        ASSERT_NEAR(s.k22, -k, 1e-12);
    }
    // The lift is kept as a float rounded up (a bound must not shrink): to 1e-7.
    EXPECT_NEAR(cavity.patchReach, r + 0.5 * r * r * k, 1e-7 * r);
    EXPECT_GE(cavity.patchReach, r + 0.5 * r * r * k * (1.0 - 1e-7));

    const GrainAsset box = withNodeShapes(bakeBox());
    double boxLargest = 0.0;
    for (const double area : box.nodes.areas) boxLargest = std::max(boxLargest, std::sqrt(area / kPi));
    EXPECT_GE(box.patchReach, boxLargest);
}

// withNodeShapes: the same asset, with a shape per node and their reach.
TEST(NodeShape, WithNodeShapesAddsTheShapesAndTheirReach)
{
    const GrainAsset a = bakeSphere();
    ASSERT_TRUE(a.nodeShapes.empty());
    EXPECT_EQ(a.patchReach, 0.0);
    const GrainAsset b = withNodeShapes(a);
    ASSERT_EQ(b.nodeShapes.size(), a.nodes.size());
    EXPECT_GT(b.patchReach, 0.0);
    EXPECT_EQ(b.nodes.positions, a.nodes.positions);
    EXPECT_EQ(b.levelSet, a.levelSet);
    const std::vector<NodeShape> again = nodeShapesOf(a);
    for (size_t i = 0; i < again.size(); ++i) {
        EXPECT_EQ(b.nodeShapes[i].normal, again[i].normal);
        EXPECT_EQ(b.nodeShapes[i].k11, again[i].k11);
        EXPECT_EQ(b.nodeShapes[i].k22, again[i].k22);
    }
}

// A node where ∇φ vanishes (here moved beyond the level set's band, where φ is its background)
// gets a flat patch facing away from the centroid.
TEST(NodeShape, ANodeWithoutAGradientGetsAFlatPatchFacingOut)
{
    GrainAsset a = bakeSphere();
    const Vec3 far(3.0 * kRadius, 1.0, -2.0);
    a.nodes.positions[5] = far;
    const std::vector<NodeShape> shapes = nodeShapesOf(a);
    const NodeShape& s = shapes[5];
    EXPECT_LT((s.normal - far.normalized()).norm(), 1e-15);
    EXPECT_NEAR(s.tangent.norm(), 1.0, 1e-15);
    EXPECT_NEAR(s.tangent.dot(s.normal), 0.0, 1e-15);
    EXPECT_EQ(s.k11, 0.0);
    EXPECT_EQ(s.k12, 0.0);
    EXPECT_EQ(s.k22, 0.0);
}
