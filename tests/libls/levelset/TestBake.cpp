// Baking: level sets, nodes and mass properties of analytic shapes and of mesh files, checked
// against closed forms with tolerances tied to the voxel size (VDP) and node spacing (SDP).
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/mesh/CentroidalNodes.h"
#include "lsdem/mesh/MeshIO.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>
#include <openvdb/tools/LevelSetMeasure.h>

using namespace lsdem;
using lsdem::kPi;

namespace {

BakeOptions spacingOptions(double voxel, double spacing)
{
    BakeOptions o;
    o.voxelSize = voxel;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = spacing;
    return o;
}

GrainAsset bake(const AnalyticShape& shape, double voxel, double spacing)
{
    std::vector<std::string> warnings;
    return bakeAnalytic(shape, spacingOptions(voxel, spacing), warnings);
}

double maxAbsPhiAtNodes(const GrainAsset& asset)
{
    LevelSetSampler sampler(*asset.levelSet);
    double worst = 0.0;
    for (const Vec3& p : asset.nodes.positions) worst = std::max(worst, std::abs(sampler.phi(p)));
    return worst;
}

} // namespace

// Node areas of an inscribed triangulation of a sphere fall short of 4πR² by O((h/R)^2): each
// flat triangle of edge h lies within a sagitta h²/(8R) of the sphere. Halving h must cut the
// error about four times (we accept < 0.4 of it).
TEST(Bake, SphereNodeAreasConvergeAtSecondOrder)
{
    const double radius = 5.0;
    const double exactArea = 4 * kPi * radius * radius;
    double previousError = 0.0;
    for (double h : {1.0, 0.5, 0.25}) {
        const GrainAsset a = bake(AnalyticShape::sphere(radius), 0.5 * h, h);
        const double error = std::abs(a.nodes.totalArea() / exactArea - 1.0);
        EXPECT_LT(error, 0.5 * (h / radius) * (h / radius)) << "h = " << h;
        if (previousError > 0.0) {
            EXPECT_LT(error, 0.4 * previousError) << "h = " << h;
        }
        previousError = error;
        // Remeshing aims at edge length h; nearest-neighbour spacing is within 30 % of it.
        EXPECT_NEAR(a.spacing.mean, h, 0.3 * h);
    }
}

// Trilinear interpolation of the exact distance |x| - R errs by at most (vox²/8)·Σ|∂²φ| ≤
// 3·vox²/(8R) near the surface, plus float storage (~1e-6 here).
TEST(Bake, SpherePhiAtNodesIsWithinTheInterpolationBound)
{
    const double radius = 5.0;
    for (double vox : {0.5, 0.25, 0.1}) {
        const GrainAsset a = bake(AnalyticShape::sphere(radius), vox, 2.5 * vox);
        EXPECT_LT(maxAbsPhiAtNodes(a), 3 * vox * vox / (8 * radius) + 1e-5) << "vox " << vox;
    }
}

TEST(Bake, SphereGradientIsUnitAndAlongTheNormal)
{
    const double radius = 5.0, vox = 0.2;
    const GrainAsset a = bake(AnalyticShape::sphere(radius), vox, 0.5);
    LevelSetSampler sampler(*a.levelSet);
    for (size_t i = 0; i < a.nodes.size(); ++i) {
        const LevelSetSample s = sampler.sample(a.nodes.positions[i]);
        // The trilinear gradient of a smooth distance errs by O(vox/R).
        EXPECT_NEAR(s.gradient.norm(), 1.0, vox / radius);
        EXPECT_GT(s.gradient.normalized().dot(a.nodes.normals[i]), std::cos(vox / radius));
        EXPECT_NEAR(a.nodes.normals[i].dot(a.nodes.positions[i].normalized()), 1.0, 1e-12);
    }
    // Deep inside, the filled interior still holds the true distance (penetrations of any
    // depth), up to the interpolation bound 3·vox²/(8r) at distance r from the centre.
    const Vec3 deep(1.0, 2.0, -1.5);
    EXPECT_NEAR(sampler.phi(deep), deep.norm() - radius, 3 * vox * vox / (8 * deep.norm()));
}

TEST(Bake, LevelSetOwnMeasuresConvergeToTheSphere)
{
    const double radius = 5.0;
    for (double vox : {0.5, 0.25}) {
        const GrainAsset a = bake(AnalyticShape::sphere(radius), vox, 1.0);
        const openvdb::FloatGrid::Ptr grid = lsdem::toFloatGrid(*a.levelSet->grid);
        openvdb::tools::LevelSetMeasure<openvdb::FloatGrid> measure(*grid);
        const double volume = 4.0 / 3.0 * kPi * radius * radius * radius;
        // OpenVDB's measure smears the surface over about a voxel: error O(vox/R) at worst.
        EXPECT_NEAR(measure.volume(true), volume, 0.5 * (vox / radius) * volume);
        EXPECT_NEAR(measure.area(true), 4 * kPi * radius * radius,
                    0.5 * (vox / radius) * 4 * kPi * radius * radius);
    }
}

TEST(Bake, BoxNodesTileItsFacesExactly)
{
    const GrainAsset a = bake(AnalyticShape::box(1, 2, 3), 0.1, 0.2);
    EXPECT_NEAR(a.nodes.totalArea(), 22.0, 1e-9);  // flat faces: the mesh area is exact
    EXPECT_NEAR(a.mass.volume, 6.0, 1e-12);
    LevelSetSampler sampler(*a.levelSet);
    const Vec3 half(0.5, 1.0, 1.5);
    for (const Vec3& p : a.nodes.positions) {
        const double phi = sampler.phi(p);
        // Away from edges the distance is linear across a voxel, so trilinear is exact (up to
        // float storage); at edges the interior distance has a kink, bounded by vox/4.
        int nearEdges = 0;
        for (int k = 0; k < 3; ++k) nearEdges += std::abs(std::abs(p[k]) - half[k]) < 0.1 + 1e-9;
        EXPECT_LT(std::abs(phi), nearEdges >= 2 ? 0.025 : 1e-6) << p.transpose();
    }
}

TEST(Bake, EllipsoidNodeAreaConvergesToLegendresArea)
{
    const double a = 3.0, b = 2.0, c = 1.0;
    const double phi = std::acos(c / a);
    const double k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
    const double area = 2 * kPi * c * c +
                        2 * kPi * a * b / std::sin(phi) *
                            (std::ellint_2(k, phi) * std::sin(phi) * std::sin(phi) +
                             std::ellint_1(k, phi) * std::cos(phi) * std::cos(phi));
    double previousError = 0.0;
    for (double h : {0.4, 0.2}) {
        const GrainAsset asset = bake(AnalyticShape::ellipsoid(a, b, c), h / 2, h);
        const double error = std::abs(asset.nodes.totalArea() / area - 1.0);
        // Curvature radius is at least c²/a = 1/3: sagitta-limited error O((h·a/c²)²).
        EXPECT_LT(error, 0.5 * (h * a / (c * c)) * (h * a / (c * c)) / 9.0) << "h " << h;
        if (previousError > 0) {
            EXPECT_LT(error, 0.4 * previousError);
        }
        previousError = error;
        // Trilinear error ≤ vox²/8 · Σ|∂ii φ| ≤ vox²/8 · (κ1 + κ2); the largest curvature sum
        // is at the tip of the long axis: a/b² + a/c².
        const double vox = h / 2;
        EXPECT_LT(maxAbsPhiAtNodes(asset), vox * vox / 8 * (a / (b * b) + a / (c * c)) + 1e-5)
            << "h " << h;
    }
}

TEST(Bake, NodeCountPlacementHitsTheCount)
{
    std::vector<std::string> warnings;
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodePlacement = NodePlacement::Count;
    for (int n : {500, 2000}) {
        o.nodeCount = n;
        const GrainAsset a = bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings);
        EXPECT_NEAR(double(a.nodes.size()), n, 0.15 * n);
        o.areaRule = AreaRule::Uniform;
    }
}

TEST(Bake, UniformAreasAreEqualAndSumToTheMeshArea)
{
    BakeOptions o = spacingOptions(0.2, 0.5);
    std::vector<std::string> warnings;
    const GrainAsset mesh = bakeAnalytic(AnalyticShape::ellipsoid(3, 2, 1), o, warnings);
    o.areaRule = AreaRule::Uniform;
    const GrainAsset uniform = bakeAnalytic(AnalyticShape::ellipsoid(3, 2, 1), o, warnings);
    ASSERT_EQ(mesh.nodes.size(), uniform.nodes.size());
    EXPECT_NEAR(uniform.nodes.totalArea(), mesh.nodes.totalArea(), 1e-9);
    for (double area : uniform.nodes.areas) EXPECT_DOUBLE_EQ(area, uniform.nodes.areas[0]);
}

// A sphere mesh in a file gives the analytic sphere's mass properties up to the polyhedral
// deficit (vertices on the sphere, edges h: relative volume error about (h/R)²/4).
TEST(Bake, SphereAndBoxMeshFilesMatchTheAnalyticShapes)
{
    test::ScratchDir dir;
    const double radius = 5.0;
    TriangleMesh sphere = AnalyticShape::sphere(radius).surfaceMesh(0.3);
    transformMesh(sphere, Mat3::Identity(), Vec3(2, -1, 3));  // off the origin on purpose
    writeMesh(sphere, dir.file("sphere.obj"));
    writeMesh(AnalyticShape::box(1, 2, 3).surfaceMesh(0.5), dir.file("box.stl"));

    std::vector<std::string> warnings;
    const GrainAsset s = bakeMeshFile(dir.file("sphere.obj"), spacingOptions(0.2, 0.5), warnings);
    const MassProperties exact = AnalyticShape::sphere(radius).massProperties();
    const double tol = 0.25 * (0.3 / radius) * (0.3 / radius) * 4;  // 4x margin on (h/R)²/4
    EXPECT_NEAR(s.mass.volume / exact.volume, 1.0, tol);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(s.mass.inertia(k, k) / exact.inertia(k, k), 1.0, 2 * tol);
    EXPECT_NEAR((s.inputFrame.centroid - Vec3(2, -1, 3)).norm(), 0.0, 1e-3);
    // The mesh's level set agrees with the exact sphere's to the polyhedral sagitta + voxel.
    LevelSetSampler sampler(*s.levelSet);
    EXPECT_NEAR(sampler.phi(Vec3(0, 0, 0)), -radius, 0.01);
    EXPECT_NEAR(sampler.phi(Vec3(radius + 0.3, 0, 0)), 0.3, 0.02);
    EXPECT_LT(maxAbsPhiAtNodes(s), 0.1 * 0.2);

    const GrainAsset b = bakeMeshFile(dir.file("box.stl"), spacingOptions(0.1, 0.2), warnings);
    EXPECT_NEAR(b.mass.volume, 6.0, 1e-9);
    const Vec3 moments = 6.0 / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4);
    // Ascending principal moments: about z (1+4), y (1+9), x (4+9).
    EXPECT_NEAR(b.mass.inertia(0, 0), moments.z(), 1e-9);
    EXPECT_NEAR(b.mass.inertia(1, 1), moments.y(), 1e-9);
    EXPECT_NEAR(b.mass.inertia(2, 2), moments.x(), 1e-9);
    EXPECT_NEAR(b.nodes.totalArea(), 22.0, 1e-6);  // remeshing keeps a box's faces flat
    EXPECT_EQ(b.provenance.sourceSha256.size(), 64u);
}

// The stored rotation and centroid map the input to the asset frame; a rotated and moved copy
// of the same input lands on the same asset (up to the box's own symmetries).
TEST(Bake, RotatedInputComesBackInTheSamePrincipalFrame)
{
    test::ScratchDir dir;
    const TriangleMesh box = AnalyticShape::box(1, 2, 3).surfaceMesh(0.5);
    TriangleMesh moved = box;
    const Mat3 q = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    transformMesh(moved, q, Vec3(10, 20, -5));
    writeMesh(box, dir.file("box.ply"));
    writeMesh(moved, dir.file("moved.ply"));
    std::vector<std::string> warnings;
    const GrainAsset a = bakeMeshFile(dir.file("box.ply"), spacingOptions(0.1, 0.25), warnings);
    const GrainAsset b = bakeMeshFile(dir.file("moved.ply"), spacingOptions(0.1, 0.25), warnings);
    // assimp reads coordinates as 32-bit floats (relative error 6e-8), so the moved copy is
    // the same box only to about 1e-7 relative; allow 1e-5.
    EXPECT_NEAR((a.mass.inertia - b.mass.inertia).norm() / a.mass.inertia.norm(), 0.0, 1e-5);
    // R_b·q·R_a^T maps asset a's frame onto asset b's: a symmetry of the box (diagonal ±1).
    const Mat3 relative = b.inputFrame.rotation * q * a.inputFrame.rotation.transpose();
    EXPECT_NEAR((relative.cwiseAbs() - Mat3::Identity()).norm(), 0.0, 1e-5);
    // Every moved input vertex, mapped by b's stored frame, lies on b's zero level set.
    LevelSetSampler sampler(*b.levelSet);
    for (const Vec3& v : moved.vertices) {
        const Vec3 inAsset = b.inputFrame.rotation * (v - b.inputFrame.centroid);
        EXPECT_LT(std::abs(sampler.phi(inAsset)), 0.1 * 0.1);
    }
}

// A mesh without sharp edges gets the nodes of a centroidal tessellation (as many as
// equilateral triangles of edge SDP would have, each owning exactly its cell of the mesh);
// a box keeps the remesher's nodes on its corners.
TEST(Bake, SmoothMeshesGetCentroidalNodesAndBoxesKeepTheirCorners)
{
    const TriangleMesh sphere = AnalyticShape::sphere(5.0).surfaceMesh(0.3);
    std::vector<std::string> warnings;
    const GrainAsset s = bakeMesh(sphere, "sphere", spacingOptions(0.2, 0.5), warnings);
    const double area = surfaceArea(sphere);
    EXPECT_EQ(s.provenance.nodeLayout, "centroidal");
    EXPECT_EQ(double(s.nodes.size()), std::round(2.0 * area / (std::sqrt(3.0) * 0.25)));
    EXPECT_NEAR(s.nodes.totalArea(), area, 1e-12 * area);
    for (size_t i = 0; i < s.nodes.size(); ++i)  // cells' mean normals: radial within 2°
        EXPECT_GT(s.nodes.normals[i].dot(s.nodes.positions[i].normalized()), std::cos(kPi / 90));

    BakeOptions count = spacingOptions(0.2, 0.5);
    count.nodePlacement = NodePlacement::Count;
    count.nodeCount = 777;
    EXPECT_EQ(bakeMesh(sphere, "sphere", count, warnings).nodes.size(), 777u);

    const GrainAsset b =
        bakeMesh(AnalyticShape::box(1, 2, 3).surfaceMesh(0.5), "box", spacingOptions(0.1, 0.2),
                 warnings);
    EXPECT_EQ(b.provenance.nodeLayout, "remesh");
    int corners = 0;
    for (const Vec3& p : b.nodes.positions) {
        std::array<double, 3> sorted{std::abs(p.x()), std::abs(p.y()), std::abs(p.z())};
        std::sort(sorted.begin(), sorted.end());
        corners += std::abs(sorted[0] - 0.5) + std::abs(sorted[1] - 1.0) +
                       std::abs(sorted[2] - 1.5) < 1e-9;
    }
    EXPECT_EQ(corners, 8);
}

// A sphere mesh with a scan's noise (every vertex moved along its radius at random) has
// thousands of sharp edges, scattered with loose ends: auto spreads its nodes centroidally
// (the count asked, exactly) and says so, naming the remesher for who wants them kept; asked
// to remesh, it keeps them (a count only about the one asked) and says nothing of noise.
TEST(Bake, AutoLayoutSpreadsTheNodesOfANoisyScanAndSaysSo)
{
    TriangleMesh noisy = AnalyticShape::sphere(1.0).surfaceMesh(1.05 / 24);  // 11,520 triangles
    std::mt19937 random(3);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);  // edges are about 0.044
    for (Vec3& v : noisy.vertices) v *= 1.0 + jitter(random);
    ASSERT_TRUE(sharpEdgesLookLikeNoise(countSharpEdges(noisy, 30.0)));
    BakeOptions o = spacingOptions(0.05, 0.15);
    std::vector<std::string> warnings;
    const GrainAsset a = bakeMesh(noisy, "noisy", o, warnings);
    auto says = [&](const char* text) {
        return std::any_of(warnings.begin(), warnings.end(), [text](const std::string& w) {
            return w.find(text) != std::string::npos;
        });
    };
    EXPECT_EQ(a.provenance.nodeLayout, "centroidal");
    EXPECT_TRUE(says("look like a scan's noise"));
    EXPECT_TRUE(says("--node-layout remesh"));
    EXPECT_EQ(double(a.nodes.size()),
              std::round(2.0 * surfaceArea(noisy) / (std::sqrt(3.0) * 0.15 * 0.15)));
    warnings.clear();
    o.nodeLayout = NodeLayout::Remesh;
    const GrainAsset r = bakeMesh(noisy, "noisy", o, warnings);
    EXPECT_EQ(r.provenance.nodeLayout, "remesh");
    EXPECT_FALSE(says("noise"));
}

// A plate thinner than the node spacing: centroidal cells would reach through it (a node on
// one face owning the other's area, its traction pushing the wrong way), so even when the
// centroidal layout is asked for, the bake remeshes and says why.
TEST(Bake, APlateThinnerThanTheSpacingIsRemeshedWithAWarning)
{
    BakeOptions o = spacingOptions(0.004, 0.1);
    o.nodeLayout = NodeLayout::Centroidal;
    std::vector<std::string> warnings;
    const GrainAsset a =
        bakeMesh(AnalyticShape::box(1.0, 1.0, 0.02).surfaceMesh(0.5), "plate", o, warnings);
    EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
        return w.find("thinner than the node spacing") != std::string::npos;
    }));
    EXPECT_NEAR(a.nodes.totalArea(), 2.0 + 4 * 0.02, 1e-6);  // remeshed: the box's faces, flat
    EXPECT_EQ(a.provenance.nodeLayout, "remesh");
}

TEST(Bake, MeshVerticesPlacementKeepsTheInputVertices)
{
    test::ScratchDir dir;
    const TriangleMesh sphere = AnalyticShape::sphere(2.0).surfaceMesh(0.4);
    writeMesh(sphere, dir.file("s.obj"));
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodePlacement = NodePlacement::MeshVertices;
    std::vector<std::string> warnings;
    const GrainAsset a = bakeMeshFile(dir.file("s.obj"), o, warnings);
    EXPECT_EQ(a.nodes.size(), sphere.vertices.size());
    EXPECT_NEAR(a.nodes.totalArea() / surfaceArea(sphere), 1.0, 1e-6);  // float coordinates
}

TEST(Bake, RefusesBadOptionsAndWarnsAboutOverfineNodes)
{
    std::vector<std::string> warnings;
    const AnalyticShape sphere = AnalyticShape::sphere(1.0);
    EXPECT_THROW(bakeAnalytic(sphere, spacingOptions(0.0, 0.1), warnings), Error);
    EXPECT_THROW(bakeAnalytic(sphere, spacingOptions(-1, 0.1), warnings), Error);
    EXPECT_THROW(bakeAnalytic(sphere, spacingOptions(0.1, std::nan("")), warnings), Error);
    EXPECT_THROW(bakeAnalytic(sphere, spacingOptions(0.6, 0.6), warnings), Error);  // too coarse
    try {
        bakeAnalytic(sphere, spacingOptions(1e-4, 0.1), warnings);  // 8e12 voxels
        FAIL() << "an enormous grid was not refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("memory budget"), std::string::npos) << e.what();
    }
    BakeOptions thinBand = spacingOptions(0.1, 0.1);
    thinBand.exteriorBandVoxels = 1;  // would bend φ near the surface (see below)
    try {
        bakeAnalytic(sphere, thinBand, warnings);
        FAIL() << "a one-voxel band was not refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--band 2"), std::string::npos) << e.what();
    }
    BakeOptions meshNodes = spacingOptions(0.1, 0.1);
    meshNodes.nodePlacement = NodePlacement::MeshVertices;
    EXPECT_THROW(bakeAnalytic(sphere, meshNodes, warnings), Error);
    warnings.clear();
    bakeAnalytic(sphere, spacingOptions(0.2, 0.05), warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("node spacing"), std::string::npos);
}

// A mesh in metres with a voxel meant for millimetres: the fix must name a voxel size the user
// can type. std::to_string printed 0.001 / 20 as "--voxel 0.000000".
TEST(Bake, ATooCoarseVoxelOnAMeshInMetresSuggestsANonzeroVoxel)
{
    std::vector<std::string> warnings;
    try {
        bakeMesh(AnalyticShape::box(0.001, 0.001, 0.001).surfaceMesh(0.0005), "cube.obj",
                 spacingOptions(0.01, 0.0002), warnings);
        FAIL() << "a voxel ten times the cube was not refused";
    } catch (const Error& e) {
        EXPECT_NE(e.fix().find("use voxel 5e-05 or smaller"), std::string::npos) << e.what();
        EXPECT_NE(e.fix().find("0.00025 is the coarsest accepted"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("thinnest extent is 0.001"), std::string::npos) << e.what();
    }
}

// Found by review: --node-spacing 1e-12 on a box overflowed the int count of its face grid
// (undefined behaviour), and tiny spacings on meshes and ellipsoids ran away in memory. A
// spacing estimated to place more nodes than --nodes allows (1e8) is refused before any work.
TEST(Bake, RefusesANodeSpacingThatWouldPlaceTooManyNodes)
{
    std::vector<std::string> warnings;
    const auto expectRefused = [&](const auto& bake, const std::string& what) {
        try {
            bake();
            ADD_FAILURE() << what << ": baked";
        } catch (const Error& e) {
            EXPECT_NE(e.problem().find("a node spacing of"), std::string::npos) << e.what();
            EXPECT_NE(e.problem().find("over the limit of 1e+08"), std::string::npos) << e.what();
            // Named as a scene or Python gives it, and as lsdem-bake does.
            EXPECT_NE(e.fix().find("use node_spacing "), std::string::npos) << e.what();
            EXPECT_NE(e.fix().find("lsdem-bake --node-spacing"), std::string::npos) << e.what();
        }
    };
    expectRefused([&] { bakeAnalytic(AnalyticShape::box(1, 1, 1), spacingOptions(0.1, 1e-12),
                                     warnings); },
                  "box");
    expectRefused([&] { bakeAnalytic(AnalyticShape::ellipsoid(1, 0.8, 0.6),
                                     spacingOptions(0.1, 1e-5), warnings); },
                  "ellipsoid");
    expectRefused([&] { bakeMesh(AnalyticShape::box(1, 1, 1).surfaceMesh(0.5), "cube.obj",
                                 spacingOptions(0.1, 1e-5), warnings); },
                  "mesh");
}

// Contact samples φ and ∇φ only where φ can be negative: in a cell with a corner inside. The
// surface then crosses the cell or the cell is inside, so every corner is inside (filled) or
// within √3 voxels outside, and an exterior band of 2 voxels holds it. Sampled anywhere
// inside, a 2-voxel band gives what a 3-voxel one gives, with fewer voxels.
TEST(Bake, ATwoVoxelBandHoldsEveryValueThatContactReads)
{
    std::vector<std::string> warnings;
    const AnalyticShape sphere = AnalyticShape::sphere(1.0);
    BakeOptions two = spacingOptions(0.1, 0.2), three = two;
    two.exteriorBandVoxels = 2;
    three.exteriorBandVoxels = 3;
    const GrainAsset a = bakeAnalytic(sphere, two, warnings);
    const GrainAsset b = bakeAnalytic(sphere, three, warnings);
    EXPECT_LT(a.levelSet->grid->activeVoxelCount(), b.levelSet->grid->activeVoxelCount());
    LevelSetSampler sa(*a.levelSet), sb(*b.levelSet);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), depth(0.0, 0.4);
    // Deeper than this a cell may have a corner in a deep brick (16 bits, rounded down by
    // less than a deep step; LevelSetBricks.h).
    const double vox = two.voxelSize;
    const double onlyWideBricks = (LevelSetBricks::kDeepVoxels - std::sqrt(3.0)) * vox;
    const double deepStep = a.levelSet->grid->deepStep();
    ASSERT_EQ(deepStep, b.levelSet->grid->deepStep());
    ASSERT_GT(a.levelSet->grid->deepBrickCount(), 0u);
    int nearSurface = 0, deeper = 0;
    for (int k = 0; k < 3000; ++k) {
        const Vec3 direction = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
        const Vec3 p = (1.0 - depth(rng)) * direction;
        const LevelSetSample x = sa.sample(p), y = sb.sample(p);
        if (1.0 - p.norm() < onlyWideBricks - 1e-9) {
            // The grids' bricks start one voxel apart, so each rounds to its 24 bits and its
            // plane bricks' steps its own way: each corner within 2.4e-7 of the float as 24 bits
            // (docs/assets.md) and then within a plane step of that (at most 2^-9 voxel), so
            // φ within twice their sum and each component of ∇φ within twice that per voxel. A
            // missing corner would be off by 0.01 or more.
            const double corner = 2.4e-7 + LevelSetBricks::kNarrowPlaneStepVoxels * vox;
            ASSERT_NEAR(x.phi, y.phi, 2.0 * corner) << "at " << p.transpose();
            ASSERT_LT((x.gradient - y.gradient).norm(), std::sqrt(3.0) * 4.0 * corner / vox)
                << "at " << p.transpose();
        } else {
            // Each corner less than a deep step below its 24-bit value, which is within
            // 2.4e-7 of the float (above), so φ within a step and 2 × 2.4e-7 and each
            // component of ∇φ within that much per voxel; and a corner in a plane brick within
            // a plane step either way, 2 of them between the grids, twice that in ∇φ.
            const double planeStep = LevelSetBricks::kNarrowPlaneStepVoxels * vox;
            const double apart = deepStep + 5e-7;
            ASSERT_NEAR(x.phi, y.phi, apart + 2.0 * planeStep) << "at " << p.transpose();
            ASSERT_LT((x.gradient - y.gradient).norm(),
                      std::sqrt(3.0) * (apart + 4.0 * planeStep) / vox)
                << "at " << p.transpose();
            ++deeper;
        }
        nearSurface += p.norm() > 0.9 ? 1 : 0;  // cells the surface crosses among them
    }
    EXPECT_GT(nearSurface, 500);
    EXPECT_GT(deeper, 1000);
}

// Volume, centroid and inertia of the baked level set itself (voxels weighted by a smeared
// Heaviside of φ, so the surface cuts voxels fractionally), against the closed forms: this
// checks that the grid holds the right shape in the right place and frame. The smeared
// boundary errs by O(vox²) relative for smooth shapes (O(vox) along a box's edges); we
// require a small error that shrinks with the voxel.
TEST(Bake, LevelSetMomentsMatchTheClosedForms)
{
    for (const AnalyticShape& shape :
         {AnalyticShape::ellipsoid(2.0, 1.5, 1.0), AnalyticShape::box(3.0, 2.0, 1.5)}) {
        const MassProperties exact = shape.massProperties();
        double previous = 1.0;
        for (double vox : {0.1, 0.05}) {
            const GrainAsset a = bake(shape, vox, 4 * vox);
            const openvdb::FloatGrid::Ptr stored = lsdem::toFloatGrid(*a.levelSet->grid);
            const auto& grid = *stored;
            double volume = 0;
            Vec3 first = Vec3::Zero();
            Mat3 second = Mat3::Zero();
            for (auto it = grid.cbeginValueOn(); it; ++it) {
                // Fraction of the voxel inside: linear ramp over one voxel across the surface.
                const double inside = std::clamp(0.5 - *it / vox, 0.0, 1.0);
                if (inside == 0.0) continue;
                const openvdb::Coord c = it.getCoord();
                const Vec3 x = a.levelSet->origin + vox * Vec3(c.x(), c.y(), c.z());
                const double w = inside * vox * vox * vox;
                volume += w;
                first += w * x;
                second += w * x * x.transpose();
            }
            const Vec3 centroid = first / volume;
            const Mat3 central = second - volume * centroid * centroid.transpose();
            const Mat3 inertia = central.trace() * Mat3::Identity() - central;
            const double error = std::max({std::abs(volume / exact.volume - 1),
                                           (inertia - exact.inertia).norm() / exact.inertia.norm(),
                                           centroid.norm() / std::cbrt(exact.volume)});
            // Measured: 0.45 % and 0.11 % (ellipsoid), 0.68 % and 0.49 % (box, whose edges are
            // smeared at first order). A grid shifted by one voxel would miss by 5 %.
            EXPECT_LT(error, 0.1 * vox / shape.halfExtents().minCoeff()) << shape.describe();
            EXPECT_LT(error, previous) << shape.describe() << " vox " << vox;
            previous = error;
        }
    }
}
