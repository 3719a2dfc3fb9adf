// The interlocked panel's geometry: blocks that tile the slab (up to the vertex holes that
// alternating faces force), neighbours on shared planes, and baked blocks that start touching
// without overlap.
#include "studies/SlabPanel.h"

#include "lsdem/contact/NodeContact.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

namespace {

SlabPanelOptions smallPanel(double angleDeg = 15.0)
{
    SlabPanelOptions o;
    o.blocksPerSide = 3;
    o.blockSize = 8.0;
    o.thickness = 3.0;
    o.angleDeg = angleDeg;
    return o;
}

/// Whether @a p is strictly inside the convex block bounded by @a faces (margin @a eps).
bool inside(const std::array<SlabFace, 6>& faces, const Vec3& p, double eps = 0.0)
{
    for (const SlabFace& f : faces)
        if (f.normal.dot(p - f.corners[0]) > -eps) return false;
    return true;
}

/// Area of the overlap of two convex polygons lying in one plane (normal @a n), by clipping
/// @a a with each edge of @a b (Sutherland–Hodgman) and the shoelace formula.
double overlapArea(std::vector<Vec3> a, const std::vector<Vec3>& b, const Vec3& n)
{
    // Make b counter-clockwise about n.
    Vec3 newell = Vec3::Zero();
    for (size_t k = 0; k < b.size(); ++k) newell += b[k].cross(b[(k + 1) % b.size()]);
    std::vector<Vec3> clip = b;
    if (newell.dot(n) < 0) std::reverse(clip.begin(), clip.end());
    for (size_t e = 0; e < clip.size() && !a.empty(); ++e) {
        const Vec3 p = clip[e], q = clip[(e + 1) % clip.size()];
        const Vec3 inward = n.cross(q - p);  // points into the ccw polygon
        std::vector<Vec3> out;
        for (size_t k = 0; k < a.size(); ++k) {
            const Vec3 u = a[k], v = a[(k + 1) % a.size()];
            const double du = inward.dot(u - p), dv = inward.dot(v - p);
            if (du >= 0) out.push_back(u);
            if ((du >= 0) != (dv >= 0)) out.push_back(u + (v - u) * (du / (du - dv)));
        }
        a = out;
    }
    Vec3 sum = Vec3::Zero();
    for (size_t k = 0; k < a.size(); ++k) sum += a[k].cross(a[(k + 1) % a.size()]);
    return 0.5 * std::abs(sum.dot(n));
}

std::vector<SlabBlock> panelAndFrame(const SlabPanel& panel)
{
    std::vector<SlabBlock> all = panel.blocks();
    all.insert(all.end(), panel.frame().begin(), panel.frame().end());
    return all;
}

} // namespace

// The block's volume against the prismatoid formula V = t/6·(A_bottom + 4·A_mid + A_top),
// exact for sections quadratic in z: A_mid = L², A_bottom = A_top = (L − 2h)(L + 2h).
TEST(SlabPanel, BlockIsAClosedSolidOfThePrismatoidVolume)
{
    for (double angle : {0.0, 10.0, 15.0, 25.0}) {
        const SlabPanel panel(smallPanel(angle));
        const double L = 8.0, t = 3.0, h = std::tan(angle * kPi / 180) * t / 2;
        const double prismatoid = t / 6 * (2 * (L - 2 * h) * (L + 2 * h) + 4 * L * L);
        const MassProperties m = computeMassProperties(panel.referenceMesh());
        EXPECT_NEAR(m.volume, prismatoid, 1e-12 * prismatoid) << angle;  // > 0: outward
        EXPECT_NEAR(panel.blockVolume(), prismatoid, 1e-12 * prismatoid) << angle;
        EXPECT_NEAR(m.centroid.norm(), 0.0, 1e-12) << angle;  // the reference is centred
        // The two shapes σ = ±1 are one solid turned a quarter: the same inertia about z and
        // the same moments about x and y.
        EXPECT_NEAR(m.inertia(0, 0), m.inertia(1, 1), 1e-12 * m.inertia(0, 0)) << angle;
    }
}

// Each block rests on its x neighbours and carries its y neighbours: a σ = +1 block's ±x faces
// look down (outward normal z < 0), its ±y faces look up; σ = −1 the other way round.
TEST(SlabPanel, FacesAlternateAroundEachBlock)
{
    const SlabPanel panel(smallPanel());
    EXPECT_EQ(panel.blocks().size(), 9u);
    EXPECT_EQ(panel.frame().size(), 12u);
    const SlabBlock& centre = panel.blocks()[panel.centralBlock()];
    EXPECT_EQ(centre.i, 1);
    EXPECT_EQ(centre.j, 1);
    EXPECT_NEAR(centre.center.head<2>().norm(), 0.0, 1e-15);
    const double sinTheta = std::sin(15.0 * kPi / 180);
    for (const SlabBlock& b : panelAndFrame(panel)) {
        const auto f = panel.faces(b);
        int down = 0, up = 0;
        for (int k = 2; k < 6; ++k) {
            const SlabFace& face = f[k];
            EXPECT_NEAR(std::abs(face.normal.z()), sinTheta, 1e-12);
            const bool alongX = std::abs(face.normal.x()) > std::abs(face.normal.y());
            const bool looksDown = face.normal.z() < 0;
            (looksDown ? down : up)++;
            EXPECT_EQ(looksDown, alongX == (b.sign > 0)) << b.name << " face " << k;
        }
        EXPECT_EQ(down, 2);
        EXPECT_EQ(up, 2);
    }
}

// Neighbours (in the panel and against the frame) lie on one plane, facing each other, and
// touch over the hexagon where their opposite trapezoids overlap: (L − h)·t/cosθ. Blocks that
// are not neighbours share no face.
TEST(SlabPanel, NeighboursShareCoplanarConformingFaces)
{
    for (double angle : {0.0, 15.0, 25.0}) {
        const SlabPanel panel(smallPanel(angle));
        const double L = 8.0, t = 3.0, h = std::tan(angle * kPi / 180) * t / 2;
        const double hexagon = (L - h) * t / std::cos(angle * kPi / 180);
        EXPECT_NEAR(panel.sharedFaceArea(), hexagon, 1e-12 * hexagon);
        const std::vector<SlabBlock> all = panelAndFrame(panel);
        for (size_t a = 0; a < all.size(); ++a)
            for (size_t b = a + 1; b < all.size(); ++b) {
                const bool panelPair = a < panel.blocks().size() || b < panel.blocks().size();
                if (!panelPair) continue;  // frame pieces never meet each other's faces
                const int di = std::abs(all[a].i - all[b].i), dj = std::abs(all[a].j - all[b].j);
                const bool neighbours = di + dj == 1;
                const auto fa = panel.faces(all[a]), fb = panel.faces(all[b]);
                int shared = 0;
                double area = 0;
                auto coplanar = [](const SlabFace& x, const SlabFace& y) {
                    if ((x.normal + y.normal).norm() > 1e-12) return false;  // facing each other
                    for (const Vec3& c : y.corners)
                        if (std::abs(x.normal.dot(c - x.corners[0])) > 1e-12) return false;
                    return true;
                };
                for (const SlabFace& x : fa)
                    for (const SlabFace& y : fb) {
                        if (!coplanar(x, y)) continue;
                        const double o = overlapArea({x.corners.begin(), x.corners.end()},
                                                     {y.corners.begin(), y.corners.end()}, x.normal);
                        if (o > 1e-9) {
                            ++shared;
                            area += o;
                        }
                    }
                EXPECT_EQ(shared, neighbours ? 1 : 0) << all[a].name << " " << all[b].name;
                if (neighbours) {
                    EXPECT_NEAR(area, hexagon, 1e-9 * hexagon) << all[a].name << " " << all[b].name;
                }
            }
    }
}

// Sample the slab on a grid: no point is inside two blocks, and the points inside none are
// exactly those in a vertex hole |x − X| < |s(z)|, |y − Y| < |s(z)| (s = tanθ·(z − t/2)) — the
// price of alternating faces. With θ = 0 the blocks are boxes and fill the slab.
TEST(SlabPanel, BlocksFillTheSlabExceptTheVertexHoles)
{
    for (double angle : {0.0, 25.0}) {
        const SlabPanel panel(smallPanel(angle));
        const double L = 8.0, t = 3.0, tanTheta = std::tan(angle * kPi / 180);
        std::vector<std::array<SlabFace, 6>> faces;
        for (const SlabBlock& b : panelAndFrame(panel)) faces.push_back(panel.faces(b));
        // Panel and frame ring (its centre line, x, y in [−2L, 2L]) without the corner cells,
        // where the frame has no block; the offsets keep the samples off the faces.
        const int m = 60;
        int holes = 0;
        for (int a = 0; a < m; ++a)
            for (int b = 0; b < m; ++b)
                for (int c = 0; c < 12; ++c) {
                    const Vec3 p(-2 * L + 4 * L * (a + 0.5 + 0.0137) / m,
                                 -2 * L + 4 * L * (b + 0.5 + 0.0291) / m, t * (c + 0.5 + 0.017) / 12);
                    const double h = tanTheta * t / 2, edge = 1.5 * L - h;
                    if (std::abs(p.x()) > edge && std::abs(p.y()) > edge) continue;  // no corner frame
                    int count = 0;
                    for (const auto& f : faces) count += inside(f, p) ? 1 : 0;
                    ASSERT_LE(count, 1) << p.transpose();
                    const double s = std::abs(tanTheta * (p.z() - t / 2));
                    // Block centres at multiples of L (n = 3), so grid vertices at L·(k + ½).
                    const double X = L * (std::round(p.x() / L - 0.5) + 0.5);
                    const double Y = L * (std::round(p.y() / L - 0.5) + 0.5);
                    const bool inHole = std::abs(p.x() - X) < s && std::abs(p.y() - Y) < s;
                    EXPECT_EQ(count == 0, inHole) << p.transpose();
                    holes += inHole;
                }
        if (angle == 0.0) {
            EXPECT_EQ(holes, 0);
        } else {
            EXPECT_GT(holes, 0);
        }
    }
}

// Volumes add up: n² blocks of L²t − tan²θ·t³/3 each (from the meshes); with θ = 0 exactly the
// slab, n²·L²·t.
TEST(SlabPanel, VolumesAddUp)
{
    for (double angle : {0.0, 15.0}) {
        SlabPanelOptions o = smallPanel(angle);
        o.blocksPerSide = 5;
        const SlabPanel panel(o);
        const double L = 8.0, t = 3.0, tanTheta = std::tan(angle * kPi / 180);
        double total = 0;
        for (const SlabBlock& b : panel.blocks()) {
            TriangleMesh mesh = panel.referenceMesh();
            transformMesh(mesh, b.rotation, b.center);
            total += computeMassProperties(mesh).volume;
        }
        const double expected = 25 * (L * L * t - tanTheta * tanTheta * t * t * t / 3);
        EXPECT_NEAR(total, expected, 1e-11 * expected);
        if (angle == 0.0) {
            EXPECT_NEAR(total, 25 * L * L * t, 1e-11 * total);
        }
    }
}

namespace {

/// Bake the block at (@a vdp, @a sdp), pose the panel and its frame, and check that no node of
/// a block is inside a neighbour (or a diagonal one). Returns the largest relative error of the
/// overlap volume Σ d·A when the central block is pushed into each neighbour by a hair, against
/// push·cosθ·(hexagon area) (the faces are tilted by θ from the push).
double bakedPanelContactError(double vdp, double sdp)
{
    const SlabPanel panel(smallPanel());
    BakeOptions bake;
    bake.voxelSize = vdp;
    bake.nodeSpacing = sdp;
    std::vector<std::string> warnings;
    const GrainAsset asset = bakeMesh(panel.referenceMesh(), "slab block", bake, warnings);
    EXPECT_NEAR(asset.mass.volume, panel.blockVolume(), 1e-9 * panel.blockVolume());
    const std::vector<SlabBlock> all = panelAndFrame(panel);
    int pairs = 0;
    for (size_t a = 0; a < all.size(); ++a)
        for (size_t b = 0; b < all.size(); ++b) {
            if (a == b || (a >= panel.blocks().size() && b >= panel.blocks().size())) continue;
            if (std::abs(all[a].i - all[b].i) > 1 || std::abs(all[a].j - all[b].j) > 1) continue;
            std::vector<NodeContact> contacts;
            NodeCheckStats stats;
            findNodeContacts(asset, slabBlockPose(all[a], asset.inputFrame), asset,
                             slabBlockPose(all[b], asset.inputFrame), contacts, stats);
            double deepest = 0;
            for (const NodeContact& c : contacts) deepest = std::max(deepest, c.depth);
            EXPECT_LT(deepest, 1e-4 * vdp) << all[a].name << " in " << all[b].name;
            ++pairs;
        }
    EXPECT_GT(pairs, 40);
    const SlabBlock& centre = panel.blocks()[panel.centralBlock()];
    double worst = 0;
    for (const SlabBlock& other : panel.blocks()) {
        if (std::abs(other.i - centre.i) + std::abs(other.j - centre.j) != 1) continue;
        RigidPose pose = slabBlockPose(centre, asset.inputFrame);
        const double push = 1e-2 * vdp;
        pose.position += push * (other.center - centre.center).normalized();
        std::vector<NodeContact> contacts;
        NodeCheckStats stats;
        findNodeContacts(asset, pose, asset, slabBlockPose(other, asset.inputFrame), contacts, stats);
        double volume = 0;
        for (const NodeContact& c : contacts) volume += c.depth * c.area;
        const double exact = push * std::cos(15.0 * kPi / 180) * panel.sharedFaceArea();
        // Lost along the hexagon's edges (perimeter ≈ 2L + 2t): a strip about a voxel wide,
        // where interpolation rounds φ up near the partner's edges (φ is convex, so trilinear
        // values are never below it), and a fraction of a node spacing, where edge nodes own
        // area on the next face.
        const double strip = (2 * 8.0 + 2 * 3.0) * (vdp + 0.25 * sdp) / panel.sharedFaceArea();
        EXPECT_NEAR(volume / exact, 1.0, strip) << other.name << " at VDP " << vdp << ", SDP " << sdp;
        worst = std::max(worst, std::abs(volume / exact - 1.0));
    }
    return worst;
}

} // namespace

// Baked (level set at VDP, nodes at SDP), posed neighbours start touching: no node is inside
// another block by more than 1e-4 VDP (the signed distance of a convex block is convex, so
// trilinear interpolation never reports more depth than the true one, which is zero here).
// The faces are conforming in the baked grains too: a push by a hair puts the shared hexagon
// into contact, up to a strip along its edges that shrinks with VDP and SDP.
TEST(SlabPanel, BakedNeighboursTouchWithoutOverlap)
{
    const double coarse = bakedPanelContactError(0.2, 0.5);
    const double fine = bakedPanelContactError(0.1, 0.25);
    EXPECT_LT(fine, 0.6 * coarse) << "first order: halving VDP and SDP about halves the error";
}

TEST(SlabPanel, BadOptionsAreErrorsNamingTheOption)
{
    SlabPanelOptions o = smallPanel();
    o.blocksPerSide = 4;
    try {
        SlabPanel p(o);
        FAIL() << "an even block count was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--blocks"), std::string::npos) << e.what();
    }
    o = smallPanel(80.0);  // tan 80°·1.5 = 8.5 mm > L/2
    EXPECT_THROW(SlabPanel{o}, Error);
    o = smallPanel();
    o.thickness = -1;
    EXPECT_THROW(SlabPanel{o}, Error);
}
