// Rigid boundaries: the reference point and the cheap "may touch" test of each shape (plane,
// finite patch, sphere, level-set obstacle), moved by their displacement; the penetrating
// nodes findBoundaryContacts reports for each shape, against distances worked out here; and a
// sphere's contacts with patch quadrature against the cap integral.
#include "lsdem/simulation/Boundary.h"
#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/NodeShape.h"
#include "lsdem/core/Constants.h"
#include "support/TestAssets.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace lsdem;

namespace {

/// A 2 × 2 × 1 box obstacle baked at coarse voxels, with its nodes (for the level-set shape).
const GrainAsset& boxAsset()
{
    static const GrainAsset asset = [] {
        BakeOptions o;
        o.voxelSize = 0.1;
        o.nodeSpacing = 0.25;
        std::vector<std::string> warnings;
        return bakeAnalytic(AnalyticShape::box(2.0, 2.0, 1.0), o, warnings);
    }();
    return asset;
}

Boundary plane(const Vec3& point, const Vec3& normal)
{
    Boundary b;
    b.shape = BoundaryShape::Plane;
    b.plane.point = point;
    b.plane.normal = normal.normalized();
    return b;
}

} // namespace

TEST(Boundary, ReferencePointIsWhereEachShapeStartedPlusItsDisplacement)
{
    Boundary p = plane(Vec3(1, 2, 3), Vec3::UnitZ());
    p.center = Vec3(9, 9, 9);  // other shapes' fields do not matter
    p.displacement = Vec3(0.5, -1, 2);
    EXPECT_EQ(p.referencePoint(), Vec3(1.5, 1, 5));

    Boundary s;
    s.shape = BoundaryShape::Sphere;
    s.center = Vec3(-1, 0, 4);
    s.radius = 2;
    s.displacement = Vec3(0, 0, -0.25);
    EXPECT_EQ(s.referencePoint(), Vec3(-1, 0, 3.75));

    Boundary l;
    l.shape = BoundaryShape::LevelSet;
    l.pose.position = Vec3(3, 2, 1);
    l.displacement = Vec3(1, 1, 1);
    EXPECT_EQ(l.referencePoint(), Vec3(4, 3, 2));
}

// A grain (centre c, radius r) may touch a plane when -r - thickness ≤ distance ≤ r, and a
// finite patch when its centre is also within the half-extents plus r along each in-plane axis.
TEST(Boundary, MayTouchAPlaneAndAFinitePatch)
{
    Boundary b = plane(Vec3(0, 0, 1), Vec3::UnitZ());
    EXPECT_TRUE(b.mayTouch(Vec3(5, -7, 1.9), 1.0));
    EXPECT_FALSE(b.mayTouch(Vec3(5, -7, 2.1), 1.0));
    EXPECT_TRUE(b.mayTouch(Vec3(0, 0, -50), 1.0));  // an infinitely thick wall
    b.displacement = Vec3(0, 0, 1.5);               // the wall rose to z = 2.5
    EXPECT_TRUE(b.mayTouch(Vec3(5, -7, 2.1), 1.0));
    EXPECT_FALSE(b.mayTouch(Vec3(5, -7, 3.6), 1.0));

    // A 4 × 2 patch (axes x and z × x = y), 0.5 thick, at z = 0.
    Boundary patch = plane(Vec3::Zero(), Vec3::UnitZ());
    patch.plane.halfU = 2.0;
    patch.plane.halfV = 1.0;
    patch.plane.thickness = 0.5;
    EXPECT_TRUE(patch.mayTouch(Vec3(2.9, 0, 0.5), 1.0));
    EXPECT_FALSE(patch.mayTouch(Vec3(3.1, 0, 0.5), 1.0));  // off the end along u
    EXPECT_TRUE(patch.mayTouch(Vec3(0, -1.9, 0.5), 1.0));
    EXPECT_FALSE(patch.mayTouch(Vec3(0, -2.1, 0.5), 1.0));  // off the side along v
    EXPECT_TRUE(patch.mayTouch(Vec3(0, 0, -1.4), 1.0));
    EXPECT_FALSE(patch.mayTouch(Vec3(0, 0, -1.6), 1.0));   // below its thickness
    patch.displacement = Vec3(1.0, 0, 0);
    EXPECT_TRUE(patch.mayTouch(Vec3(3.1, 0, 0.5), 1.0));   // the patch moved along
}

TEST(Boundary, MayTouchASphereAndAnObstacleByTheirBoundingSpheres)
{
    Boundary s;
    s.shape = BoundaryShape::Sphere;
    s.center = Vec3(0, 0, 5);
    s.radius = 2.0;
    EXPECT_TRUE(s.mayTouch(Vec3(0, 2.9, 5), 1.0));
    EXPECT_FALSE(s.mayTouch(Vec3(0, 3.1, 5), 1.0));
    s.displacement = Vec3(0, 0.5, 0);
    EXPECT_TRUE(s.mayTouch(Vec3(0, 3.1, 5), 1.0));

    Boundary l;
    l.shape = BoundaryShape::LevelSet;
    l.asset = std::shared_ptr<const GrainAsset>(&boxAsset(), [](const GrainAsset*) {});
    l.pose.position = Vec3(1, 1, 1);
    const double reach = boxAsset().boundingRadius + 0.5;
    EXPECT_TRUE(l.mayTouch(Vec3(1, 1, 1) + (reach - 1e-9) * Vec3(0.6, 0, 0.8), 0.5));
    EXPECT_FALSE(l.mayTouch(Vec3(1, 1, 1) + (reach + 1e-9) * Vec3(0.6, 0, 0.8), 0.5));
    l.displacement = Vec3(0, 0, 0.1);
    EXPECT_TRUE(l.mayTouch(Vec3(1, 1, 1) + (reach + 1e-9) * Vec3(0.6, 0, 0.8), 0.5));
}

// Nodes behind a tilted, moved plane: depth = distance behind it, the plane's normal, the point
// halfway back to it; a finite patch keeps only the nodes over it and less than its thickness
// behind.
TEST(Boundary, PlaneContactsAreTheNodesBehindIt)
{
    const GrainAsset a = lsdem::test::sixNodeAsset(0.5);
    RigidPose pose;
    pose.position = Vec3(0.2, 0.0, 0.6);
    const Vec3 n = Vec3(0, 0.6, 0.8);
    Boundary b = plane(Vec3(0, 0, -0.5), n);
    b.displacement = Vec3(0, 0, 0.25);  // now through (0, 0, -0.25)
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findBoundaryContacts(a, pose, b, contacts, stats);
    // Signed distances (x - (0,0,-0.25))·n = 0.6·y + 0.8·(z + 0.25): node 3 (0.2,-1,0.6) is
    // 0.08 in front, node 5 (0.2,0,-0.4) 0.12 behind, the others further in front.
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_EQ(contacts[0].node, 5);
    EXPECT_NEAR(contacts[0].depth, 0.12, 1e-15);
    EXPECT_EQ(contacts[0].normal, b.plane.normal);
    EXPECT_LT((contacts[0].point - (Vec3(0.2, 0, -0.4) + 0.06 * b.plane.normal)).norm(), 1e-15);
    EXPECT_EQ(contacts[0].area, 0.5);
    EXPECT_EQ(stats.nodesConsidered, 6);

    // A finite patch: the same plane, only 0.1 wide along x, so the node at x = 0.2 is off it.
    b.plane.axisU = Vec3::UnitX();
    b.plane.halfU = 0.1;
    b.plane.halfV = 10.0;
    contacts.clear();
    findBoundaryContacts(a, pose, b, contacts, stats);
    EXPECT_TRUE(contacts.empty());
    b.plane.halfU = 0.3;
    b.plane.thickness = 0.1;  // node 5 is 0.12 behind: too deep for this thin patch
    findBoundaryContacts(a, pose, b, contacts, stats);
    EXPECT_TRUE(contacts.empty());
    b.plane.thickness = 0.15;
    findBoundaryContacts(a, pose, b, contacts, stats);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_EQ(contacts[0].node, 5);
}

// Nodes inside a sphere indenter: depth R - |x - c|, normal (x - c)/|x - c| (pushing the node
// out), point halfway to the sphere's surface; the rotation of the grain is applied to nodes.
TEST(Boundary, SphereContactsAreTheNodesInsideIt)
{
    const GrainAsset a = lsdem::test::sixNodeAsset(0.5);
    RigidPose pose;
    pose.orientation = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));  // x node -> +y
    Boundary s;
    s.shape = BoundaryShape::Sphere;
    s.center = Vec3(0.3, 1.5, 0.4);
    s.radius = 0.9;
    s.displacement = Vec3(-0.3, 0.0, -0.4);  // now at (0, 1.5, 0)
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findBoundaryContacts(a, pose, s, contacts, stats);
    // Only node 0 (+x in the asset, +y in the world) is inside: 0.5 from the centre.
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_EQ(contacts[0].node, 0);
    EXPECT_NEAR(contacts[0].depth, 0.4, 1e-15);
    EXPECT_LT((contacts[0].normal - Vec3(0, -1, 0)).norm(), 1e-15);
    EXPECT_LT((contacts[0].point - Vec3(0, 0.8, 0)).norm(), 1e-15);

    // A sphere far away: the whole grain is culled.
    s.displacement = Vec3(10, 0, 0);
    NodeCheckStats far;
    contacts.clear();
    findBoundaryContacts(a, pose, s, contacts, far);
    EXPECT_TRUE(contacts.empty());
    EXPECT_EQ(far.nodesCulled, 6);
}

// A sphere indenter on a baked grain with node blocks: the block culling keeps exactly the
// contacts of a full scan, each against the exact sphere distance.
TEST(Boundary, SphereBlockCullingKeepsEveryContact)
{
    const GrainAsset& withBlocks = boxAsset();
    GrainAsset plain = withBlocks;
    plain.nodeBlocks.clear();
    RigidPose pose;
    pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));
    // The indenter 0.4 above a point of the turned top face: 0.2 deep, a cap of ~10 nodes.
    Boundary s;
    s.shape = BoundaryShape::Sphere;
    s.center = pose.toWorld(Vec3(0.3, -0.2, 0.5)) + 0.4 * (pose.orientation * Vec3::UnitZ());
    s.radius = 0.6;
    std::vector<NodeContact> blocked, scanned;
    NodeCheckStats blockedStats, scannedStats;
    findBoundaryContacts(withBlocks, pose, s, blocked, blockedStats);
    findBoundaryContacts(plain, pose, s, scanned, scannedStats);
    ASSERT_GT(scanned.size(), 3u);
    ASSERT_EQ(blocked.size(), scanned.size());
    for (size_t k = 0; k < scanned.size(); ++k) {
        EXPECT_EQ(blocked[k].node, scanned[k].node);
        EXPECT_EQ(blocked[k].depth, scanned[k].depth);
        const Vec3 x = pose.toWorld(plain.nodes.positions[scanned[k].node]);
        EXPECT_NEAR(scanned[k].depth, 0.6 - (x - s.center).norm(), 1e-15);
    }
    EXPECT_GT(blockedStats.nodesCulled, scannedStats.nodesCulled);
}

// An obstacle is a level set posed like a grain: its contacts are those of the narrow phase
// against it at its moved pose.
TEST(Boundary, LevelSetContactsAreTheNarrowPhaseAtTheMovedPose)
{
    const GrainAsset& box = boxAsset();
    Boundary l;
    l.shape = BoundaryShape::LevelSet;
    l.asset = std::shared_ptr<const GrainAsset>(&box, [](const GrainAsset*) {});
    l.pose.position = Vec3(0, 0, -1.0);
    l.pose.orientation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX()));
    l.displacement = Vec3(0.1, 0, 0.2);
    const GrainAsset grain = lsdem::test::sixNodeAsset(0.5);
    // The grain's -z node 0.2 under the top face of the turned box, whose centre is now
    // (0.1, 0, -0.8); its other nodes are clear of the box.
    RigidPose pose;
    pose.position = Vec3(0.05, 0.0, 0.2 + 0.3 / std::cos(0.2));
    std::vector<NodeContact> contacts, direct;
    NodeCheckStats stats;
    findBoundaryContacts(grain, pose, l, contacts, stats);
    RigidPose moved = l.pose;
    moved.position += l.displacement;
    findNodeContacts(grain, pose, box, moved, direct, stats);
    ASSERT_EQ(contacts.size(), 1u);  // the -z node, inside the top face
    ASSERT_EQ(direct.size(), 1u);
    EXPECT_EQ(contacts[0].node, 5);
    EXPECT_EQ(contacts[0].depth, direct[0].depth);
    EXPECT_EQ(contacts[0].normal, direct[0].normal);
    // With the grain's nodes near it remembered (a simulation's slot keeps them; they need
    // the nodes in blocks), the same contact, and the list is made for the next call.
    GrainAsset grouped = lsdem::test::sixNodeAsset(0.5);
    grouped.nodeBlocks = groupNodesIntoBlocks(grouped.nodes);
    CandidateBlocks remembered;
    std::vector<NodeContact> withList;
    findBoundaryContacts(grouped, pose, l, withList, stats, &remembered);
    EXPECT_TRUE(remembered.valid);
    ASSERT_EQ(withList.size(), 1u);
    EXPECT_EQ(withList[0].node, 5);
    EXPECT_EQ(withList[0].depth, direct[0].depth);
    EXPECT_EQ(withList[0].normal, direct[0].normal);
    // The top face is 0.5 from the box's centre along its turned z axis. Near a face the box's
    // distance is linear, which trilinear interpolation reproduces (float storage: ~1e-7).
    const Vec3 up = l.pose.orientation * Vec3::UnitZ();
    const Vec3 node = pose.position - Vec3::UnitZ();
    const double depth = 0.5 - (node - Vec3(0.1, 0, -0.8)).dot(up);
    EXPECT_NEAR(depth, 0.2, 1e-12);
    EXPECT_NEAR(contacts[0].depth, depth, 1e-6);
    EXPECT_LT((contacts[0].normal - up).norm(), 1e-6);
    // Without the displacement the node is only 0.2 deep: the displacement is applied.
    l.displacement = Vec3::Zero();
    contacts.clear();
    findBoundaryContacts(grain, pose, l, contacts, stats);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].depth, depth - 0.2 * up.z(), 1e-6);
}

// A cylinder holds grains inside: a grain may touch it when its centre is within its radius of
// the wall (distance from the axis + r ≥ R), whatever its height along the axis.
TEST(Boundary, MayTouchACylinderFromInside)
{
    Boundary c;
    c.shape = BoundaryShape::Cylinder;
    c.center = Vec3(1, 2, 0);
    c.axis = Vec3::UnitZ();
    c.radius = 3.0;
    EXPECT_FALSE(c.mayTouch(Vec3(1, 2, 50), 1.0));       // on the axis, far up
    EXPECT_FALSE(c.mayTouch(Vec3(2.9, 2, -7), 1.0));     // 1.9 from the axis: 0.1 clear
    EXPECT_TRUE(c.mayTouch(Vec3(3.1, 2, -7), 1.0));
    EXPECT_TRUE(c.mayTouch(Vec3(1, 2 - 2.1, 0), 1.0));
    EXPECT_TRUE(c.mayTouch(Vec3(10, 2, 0), 1.0));        // outside: certainly in contact
    c.displacement = Vec3(0.5, 0, 9);                    // the axis moved to x = 1.5
    EXPECT_FALSE(c.mayTouch(Vec3(3.1, 2, -7), 1.0));
    EXPECT_EQ(c.referencePoint(), Vec3(1.5, 2, 9));
}

// Nodes outside a cylinder of tilted axis: depth ρ - R (ρ the distance from the axis), the
// normal pointing back to the axis, the point halfway back to the wall.
TEST(Boundary, CylinderContactsAreTheNodesOutsideIt)
{
    const GrainAsset a = lsdem::test::sixNodeAsset(0.5);
    Boundary c;
    c.shape = BoundaryShape::Cylinder;
    c.axis = Vec3(0, 0.6, 0.8);  // in the y–z plane
    c.center = Vec3(0.5, 0, 0);
    c.radius = 1.2;
    c.displacement = Vec3(-0.5, 0, 0);  // the axis now through the origin
    RigidPose pose;
    pose.position = Vec3(0.5, 0, 0);
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findBoundaryContacts(a, pose, c, contacts, stats);
    // Node 0 at (1.5, 0, 0) is 1.5 from the axis (it is perpendicular to it): 0.3 out. Node 2
    // (0.5, 1, 0): the axial part is 0.6, so the radial offset is (0.5, 1, 0) - 0.6·axis =
    // (0.5, 0.64, -0.48), length sqrt(0.25 + 0.4096 + 0.2304) = 0.943: inside; the others are
    // nearer the axis.
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_EQ(contacts[0].node, 0);
    EXPECT_NEAR(contacts[0].depth, 0.3, 1e-15);
    EXPECT_LT((contacts[0].normal - Vec3(-1, 0, 0)).norm(), 1e-15);
    EXPECT_LT((contacts[0].point - Vec3(1.35, 0, 0)).norm(), 1e-15);
    EXPECT_EQ(contacts[0].area, 0.5);

    // Deep inside, the whole grain is culled.
    pose.position = Vec3::Zero();
    NodeCheckStats inside;
    contacts.clear();
    findBoundaryContacts(a, pose, c, contacts, inside);
    EXPECT_TRUE(contacts.empty());
    EXPECT_EQ(inside.nodesCulled, 6);
}

// On a baked grain with node blocks pressed against the wall, the block culling keeps exactly
// the contacts of a full scan, each at the exact distance from the axis.
TEST(Boundary, CylinderBlockCullingKeepsEveryContact)
{
    const GrainAsset& withBlocks = boxAsset();
    GrainAsset plain = withBlocks;
    plain.nodeBlocks.clear();
    RigidPose pose;
    pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));
    pose.position = Vec3(1.3, 0.2, 5.0);
    Boundary c;
    c.shape = BoundaryShape::Cylinder;
    c.radius = 2.0;
    std::vector<NodeContact> blocked, scanned;
    NodeCheckStats blockedStats, scannedStats;
    findBoundaryContacts(withBlocks, pose, c, blocked, blockedStats);
    findBoundaryContacts(plain, pose, c, scanned, scannedStats);
    ASSERT_GT(scanned.size(), 3u);
    ASSERT_EQ(blocked.size(), scanned.size());
    for (size_t k = 0; k < scanned.size(); ++k) {
        EXPECT_EQ(blocked[k].node, scanned[k].node);
        EXPECT_EQ(blocked[k].depth, scanned[k].depth);
        const Vec3 x = pose.toWorld(plain.nodes.positions[scanned[k].node]);
        EXPECT_NEAR(scanned[k].depth, std::hypot(x.x(), x.y()) - 2.0, 1e-15);
        EXPECT_GT(scanned[k].depth, 0.0);
    }
    EXPECT_GT(blockedStats.nodesCulled, scannedStats.nodesCulled);
}

namespace {

/// An orifice plate of tilted axis: hole radius 1.5, thickness 0.4, centre (0.3, −0.2, 0.1).
Boundary tiltedOrifice()
{
    Boundary o;
    o.shape = BoundaryShape::Orifice;
    o.center = Vec3(0.3, -0.2, 0.1);
    o.axis = Vec3(0.6, 0, 0.8);
    o.radius = 1.5;
    o.thickness = 0.4;
    return o;
}

/// The distance from @a x to the nearest of many points on the plate's surface near it (its
/// two faces out to 1.2 beyond the hole, and the hole's wall), sampled every ≤ 0.0021: an
/// estimate independent of the contact's formula, at most 0.0015 too long.
double sampledDistanceToPlate(const Boundary& o, const Vec3& x)
{
    const Vec3 u = o.axis.unitOrthogonal(), v = o.axis.cross(u);
    const double half = 0.5 * o.thickness;
    double best = std::numeric_limits<double>::infinity();
    const int turns = 8000;
    for (int k = 0; k < turns; ++k) {
        const double angle = 2.0 * kPi * k / turns;
        const Vec3 radial = std::cos(angle) * u + std::sin(angle) * v;
        for (double rho = o.radius; rho <= o.radius + 1.2; rho += 0.002)
            for (double h : {-half, half})
                best = std::min(best, (o.center + rho * radial + h * o.axis - x).norm());
        for (double h = -half; h <= half; h += 0.002)
            best = std::min(best, (o.center + o.radius * radial + h * o.axis - x).norm());
    }
    return best;
}

} // namespace

// Nodes inside the plate leave it by its nearer face or the hole's wall: the depth is the
// distance to the plate's surface (checked against points sampled on it), the normal leads
// there, and nodes in the hole or beyond the faces touch nothing.
TEST(Boundary, OrificeContactsAreTheDistanceToThePlatesSurface)
{
    const Boundary o = tiltedOrifice();
    const Vec3 u = o.axis.unitOrthogonal(), v = o.axis.cross(u);
    // Nodes in the plate's frame: (radial distance, angle, height), a grain of one node each.
    struct Probe { double rho, angle, h; bool inside; };
    const std::vector<Probe> probes = {
        {1.9, 0.3, 0.15, true},    // near the upper face
        {2.4, 2.0, -0.12, true},   // near the lower face
        {1.6, 4.0, 0.02, true},    // near the hole's wall
        {1.62, 1.1, 0.17, true},   // near the rim's corner, face side
        {1.53, 5.5, -0.1, true},   // near the rim's corner, hole side
        {1.4, 0.7, 0.0, false},    // in the hole
        {3.0, 2.2, 0.25, false},   // above the plate
        {1.45, 3.3, -0.25, false}, // below and inside the rim
    };
    for (const Probe& p : probes) {
        GrainAsset one;
        one.nodes.positions.push_back(Vec3::Zero());
        one.nodes.normals.push_back(Vec3::UnitZ());
        one.nodes.areas.push_back(0.25);
        one.boundingRadius = 0.0;
        RigidPose pose;
        const Vec3 radial = std::cos(p.angle) * u + std::sin(p.angle) * v;
        pose.position = o.center + p.rho * radial + p.h * o.axis;
        std::vector<NodeContact> contacts;
        NodeCheckStats stats;
        findBoundaryContacts(one, pose, o, contacts, stats);
        ASSERT_EQ(contacts.size(), p.inside ? 1u : 0u) << "rho " << p.rho << " h " << p.h;
        if (!p.inside) continue;
        const NodeContact& c = contacts[0];
        EXPECT_NEAR(c.depth, sampledDistanceToPlate(o, pose.position), 2e-3) << "rho " << p.rho;
        // Pushed by its depth along the normal, the node is on the surface.
        EXPECT_LT(sampledDistanceToPlate(o, pose.position + c.depth * c.normal), 2e-3);
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_LT((c.point - (pose.position + 0.5 * c.depth * c.normal)).norm(), 1e-15);
        EXPECT_EQ(c.area, 0.25);
    }
}

// A grain in the hole clear of the rim, or above the plate, is culled whole; one may touch the
// plate when its sphere reaches either face outside the hole.
TEST(Boundary, MayTouchAnOrificeOnlyNearThePlateOutsideTheHole)
{
    Boundary o;
    o.shape = BoundaryShape::Orifice;
    o.center = Vec3(0, 0, 1);
    o.radius = 3.0;
    o.thickness = 0.5;
    EXPECT_FALSE(o.mayTouch(Vec3(0, 0, 1), 1.0));       // falling through the middle
    EXPECT_FALSE(o.mayTouch(Vec3(1.9, 0, 1), 1.0));     // 0.1 clear of the hole's wall
    EXPECT_TRUE(o.mayTouch(Vec3(2.1, 0, 1), 1.0));
    EXPECT_FALSE(o.mayTouch(Vec3(10, 0, 2.3), 1.0));    // 0.05 above the upper face
    EXPECT_TRUE(o.mayTouch(Vec3(10, 0, 2.2), 1.0));
    EXPECT_TRUE(o.mayTouch(Vec3(10, 0, -0.2), 1.0));    // under the lower face
    o.displacement = Vec3(0, 0, -1);
    EXPECT_FALSE(o.mayTouch(Vec3(10, 0, 2.2), 1.0));
    EXPECT_EQ(o.referencePoint(), Vec3(0, 0, 0));

    const GrainAsset a = lsdem::test::sixNodeAsset(0.5);
    RigidPose pose;
    pose.position = Vec3(0.5, 0, 0);
    std::vector<NodeContact> contacts;
    NodeCheckStats stats;
    findBoundaryContacts(a, pose, o, contacts, stats);
    EXPECT_TRUE(contacts.empty());
    EXPECT_EQ(stats.nodesCulled, 6);
}

// On a baked grain pressed into the rim, the block culling keeps exactly the contacts of a
// full scan.
TEST(Boundary, OrificeBlockCullingKeepsEveryContact)
{
    const GrainAsset& withBlocks = boxAsset();
    GrainAsset plain = withBlocks;
    plain.nodeBlocks.clear();
    Boundary o = tiltedOrifice();
    o.radius = 1.0;
    RigidPose pose;
    pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));
    pose.position = o.center + 0.6 * o.axis + 0.5 * o.axis.unitOrthogonal();
    std::vector<NodeContact> blocked, scanned;
    NodeCheckStats blockedStats, scannedStats;
    findBoundaryContacts(withBlocks, pose, o, blocked, blockedStats);
    findBoundaryContacts(plain, pose, o, scanned, scannedStats);
    ASSERT_GT(scanned.size(), 3u);
    ASSERT_EQ(blocked.size(), scanned.size());
    bool face = false, wall = false;
    for (size_t k = 0; k < scanned.size(); ++k) {
        EXPECT_EQ(blocked[k].node, scanned[k].node);
        EXPECT_EQ(blocked[k].depth, scanned[k].depth);
        EXPECT_EQ(blocked[k].normal, scanned[k].normal);
        face = face || std::abs(scanned[k].normal.dot(o.axis)) == 1.0;
        wall = wall || std::abs(scanned[k].normal.dot(o.axis)) < 1e-12;
    }
    EXPECT_TRUE(face && wall);  // the box straddles the rim
    EXPECT_GT(blockedStats.nodesCulled, scannedStats.nodesCulled);
}

// A ball grain (R₁ = 2, ~2000 nodes, spacing ~0.16) pressed by δ into a sphere boundary
// (R₂ = 3): the depth at a point of the ball's surface at polar angle θ from the axis is
// R₂ − √(a − b·cos θ), a = R₁² + D², b = 2R₁D, D = R₁ + R₂ − δ the centres' distance, so the
// integral of the depth over the ball's surface is, with u = cos θ from u₀ (where the depth is
// 0: a − b·u₀ = R₂²) to 1 (where √(a − b) = D − R₁),
//   2πR₁²·[R₂(1 − u₀) − (2/3b)(R₂³ − (D − R₁)³)]   (≈ π·δ²·R₁R₂/(R₁ + R₂) for small δ),
// what k·area·depth summed over the contacts should give. The nodes as points see a cap
// narrower than two spacings (radius √(2δR₁R₂/(R₁ + R₂)) = 0.11 to 0.22) as a handful of
// depths; the patches integrate the depth (the sphere's bend included) over each node's patch.
// Over 64 random turns, the patches' RMS error is below 0.3 of the nodes' (measured 0.13, 0.15
// and 0.14 at δ = 0.005, 0.01, 0.02; the nodes' own 34 % to 4.4 %; with the cells scaled to
// the nodes' tributary areas 0.16 to 0.31, with disks of the nodes' areas 0.21 to 0.64), below
// a quarter at the narrowest cap (0.13), and their mean within 1 % (measured ≤ 0.54 %).
TEST(Boundary, SpherePatchesFollowTheCapIntegralMoreCloselyThanNodes)
{
    const double R1 = 2.0, R2 = 3.0;
    BakeOptions o;
    o.voxelSize = 0.05;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = 2000;
    std::vector<std::string> warnings;
    const GrainAsset ball = withNodeShapes(bakeAnalytic(AnalyticShape::sphere(R1), o, warnings));
    std::mt19937 rng(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (double delta : {0.005, 0.01, 0.02}) {
        const double D = R1 + R2 - delta, a = R1 * R1 + D * D, b = 2.0 * R1 * D;
        const double u0 = (a - R2 * R2) / b;
        const double exact = 2.0 * kPi * R1 * R1 *
                             (R2 * (1.0 - u0) - 2.0 / (3.0 * b) * (std::pow(R2, 3) - std::pow(D - R1, 3)));
        Boundary indenter;
        indenter.shape = BoundaryShape::Sphere;
        indenter.center = Vec3(0, 0, D);
        indenter.radius = R2;
        double nodeSquares = 0.0, patchSquares = 0.0, patchSum = 0.0;
        const int turns = 64;
        for (int k = 0; k < turns; ++k) {
            RigidPose pose;
            pose.orientation = Quat(Eigen::Vector4d(normal(rng), normal(rng), normal(rng),
                                                    normal(rng)).normalized());
            double error[2];
            for (int patches = 0; patches < 2; ++patches) {
                std::vector<NodeContact> contacts;
                NodeCheckStats stats;
                findBoundaryContacts(ball, pose, indenter, contacts, stats, nullptr, patches == 1);
                double sum = 0.0;
                for (const NodeContact& c : contacts) sum += c.area * c.depth;
                error[patches] = sum / exact - 1.0;
            }
            nodeSquares += error[0] * error[0];
            patchSquares += error[1] * error[1];
            patchSum += error[1];
        }
        const double nodeRms = std::sqrt(nodeSquares / turns), patchRms = std::sqrt(patchSquares / turns);
        EXPECT_LT(patchRms, 0.3 * nodeRms) << "delta " << delta << ": patches " << patchRms;
        if (delta == 0.005) {
            EXPECT_LT(patchRms, 0.25 * nodeRms) << "patches " << patchRms << ", nodes " << nodeRms;
        }
        EXPECT_LT(std::abs(patchSum / turns), 0.01) << "delta " << delta;
    }
}
