// The interlocked slab study (tools/studies/SlabStudy): flat contacts of a baked block against
// the closed form kn*·A·δ (on a plane and on its neighbour), the scene and its TOML, a tiny
// panel run (equilibrium, the central block moving most), and lsdem-study slab as a user runs it.
#include "studies/SlabStudy.h"

#include "support/TestSupport.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Boundary.h"
#include "lsdem/contact/PairContact.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>

using namespace lsdem;
using lsdem::kPi;
using lsdem::test::runCommand;

namespace {

const std::string kStudy = LSDEM_STUDY_EXE;

SlabStudyOptions tinyOptions()
{
    SlabStudyOptions o;
    o.panel.blocksPerSide = 3;
    o.sdps = {1.0};
    o.fixedVdp = 0.3;
    o.formulations = {Formulation::Adapted};
    o.twoWay = false;
    o.deltaMax = 0.3;
    o.samples = 30;
    return o;
}

/// Frictionless adapted model with the study's kn*.
ContactModel pressModel(const SlabStudyOptions& o)
{
    ContactModel m = slabContactModel(o, Formulation::Adapted);
    m.shearStiffness = 0.0;
    m.friction = 0.0;
    return m;
}

/// The force on a block at @a pose from a plane boundary (adapted law, no shear).
Vec3 forceFromPlane(const GrainAsset& block, const RigidPose& pose, const BoundarySpec& plane,
                    const ContactModel& model)
{
    const Boundary b = makeBoundary(plane, nullptr);
    ContactGrain grain, wall;
    grain.asset = &block;
    grain.pose = pose;
    ContactSide side;
    side.tester = &grain;
    side.other = &wall;
    NodeCheckStats stats;
    findBoundaryContacts(block, pose, b, side.contacts, stats);
    return resolveContact(&side, 1, model, 0.0, nullptr).forceOnFirst;
}

/// Relative error of the force of a block's bottom face pressed by δ into a plane, against
/// kn*·A_bottom·δ, A_bottom = (L − 2h)(L + 2h).
double flatPressError(const SlabStudyOptions& o, double vdp, double sdp, double delta)
{
    const SlabPanel panel(o.panel);
    const auto block = bakeSlabBlock(panel, vdp, sdp);
    SlabBlock rest = panel.blocks()[panel.centralBlock()];
    RigidPose pose = slabBlockPose(rest, block->inputFrame);  // bottom face on z = 0
    pose.position.z() -= delta;
    BoundarySpec floor;
    floor.shape = BoundaryShape::Plane;
    floor.point = Vec3::Zero();
    floor.normal = Vec3::UnitZ();
    const Vec3 f = forceFromPlane(*block, pose, floor, pressModel(o));
    const double L = o.panel.blockSize, h = panel.overhang();
    const double exact = slabStiffness(o).knStar * (L - 2 * h) * (L + 2 * h) * delta;
    EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-9 * exact);  // a flat press pushes straight up
    return f.z() / exact - 1.0;
}

/// The same for a block pressed onto its x neighbour across their shared inclined face, both
/// baked grains (symmetric testing through the level sets): kn*·A_hexagon·δ along the normal.
double facePressError(const SlabStudyOptions& o, double vdp, double sdp, double delta)
{
    const SlabPanel panel(o.panel);
    const auto block = bakeSlabBlock(panel, vdp, sdp);
    const SlabBlock& a = panel.blocks()[panel.centralBlock()];
    const SlabBlock& b = panel.blocks()[panel.centralBlock() + 1];  // its +x neighbour
    const SlabFace shared = panel.faces(a)[3];                       // +x face of a
    ContactGrain first, second;
    first.asset = second.asset = block.get();
    first.index = 0;
    second.index = 1;
    first.pose = slabBlockPose(a, block->inputFrame);
    first.pose.position += delta * shared.normal;  // into b, perpendicular to the face
    second.pose = slabBlockPose(b, block->inputFrame);
    NodeCheckStats stats;
    const PairForces f = computePairContact(first, second, pressModel(o), 0.0, nullptr, stats);
    const double exact = slabStiffness(o).knStar * panel.sharedFaceArea() * delta;
    // Only normal forces: the sum points along the face normal, pushing a back.
    EXPECT_LT((f.forceOnFirst + f.forceOnFirst.norm() * shared.normal).norm(),
              0.02 * f.forceOnFirst.norm());
    return -f.forceOnFirst.dot(shared.normal) / exact - 1.0;
}

} // namespace

// A block's bottom face pressed flat into a plane: the adapted force is kn*·A·δ up to the
// nodes on the bottom edges, which own a third of the side triangles next to them too: about
// (√3/4)·SDP of extra area per unit length of edge, so the error is positive, predictable and
// shrinks in proportion to SDP (the plane's distance is exact, so VDP plays no part).
TEST(SlabStudy, BlockPressedFlatOntoAPlaneGivesKnStarAreaDelta)
{
    SlabStudyOptions o = tinyOptions();
    const SlabPanel panel(o.panel);
    const double L = o.panel.blockSize, h = panel.overhang();
    const double perimeter = 4 * L, area = (L - 2 * h) * (L + 2 * h);
    double previous = 0;
    for (double sdp : {0.5, 0.25}) {
        const double e = flatPressError(o, 0.2, sdp, 0.01);
        // Edge nodes on an equilateral mesh of edge SDP own (√3/4)·SDP of side area per unit
        // length of edge (a third of each side triangle at the edge, one per SDP of edge,
        // counted from both its edge vertices or its one).
        const double predicted = std::sqrt(3.0) / 4 * sdp * perimeter / area;
        EXPECT_NEAR(e, predicted, 0.25 * predicted) << sdp;
        if (previous > 0) {
            EXPECT_LT(e, 0.65 * previous) << "first order in SDP";
        }
        previous = e;
        // Linear in δ: the same relative error at twice the depth (nodes of the side faces
        // stay above the plane while δ < the first row's height).
        EXPECT_NEAR(flatPressError(o, 0.2, sdp, 0.02), e, 1e-9) << sdp;
    }
}

// A block pressed onto its neighbour across their shared inclined face (level set against
// level set): kn*·A_hexagon·δ, up to a strip along the hexagon's edges about a voxel wide
// (interpolation rounds φ up near the partner's edges: the signed distance of a convex block is
// convex) and a fraction of a node spacing (edge nodes' area on the next face). Halving both
// VDP and SDP about halves the error.
TEST(SlabStudy, BlockPressedOntoItsNeighbourGivesKnStarHexagonDelta)
{
    SlabStudyOptions o = tinyOptions();
    const SlabPanel panel(o.panel);
    const double perimeter = 2 * o.panel.blockSize + 2 * o.panel.thickness;  // of the hexagon, about
    const double coarse = facePressError(o, 0.2, 0.5, 0.02);
    const double fine = facePressError(o, 0.1, 0.25, 0.02);
    EXPECT_LT(std::abs(coarse), perimeter * (0.2 + 0.25 * 0.5) / panel.sharedFaceArea());
    EXPECT_LT(std::abs(fine), perimeter * (0.1 + 0.25 * 0.25) / panel.sharedFaceArea());
    EXPECT_LT(std::abs(fine), 0.65 * std::abs(coarse)) << "first order in VDP and SDP";
}

// The scene: n² free blocks posed from the asset's principal frame, 4n fixed frame blocks and
// the indenter just touching the central block's top; its TOML reads back to the same scene.
TEST(SlabStudy, SceneAndItsTomlAgree)
{
    lsdem::test::ScratchDir dir;
    SlabStudyOptions o = tinyOptions();
    const SlabPanel panel(o.panel);
    const auto block = bakeSlabBlock(panel, 0.3, 1.0);
    const double dt = slabTimeStep(o, panel, *block, Formulation::Adapted);
    Scene scene = makeSlabScene(o, Formulation::Adapted, block, dt);
    EXPECT_EQ(scene.assets.front().loaded, block);  // held in memory, no file needed
    ASSERT_EQ(scene.grains.size(), 9u);
    ASSERT_EQ(scene.boundaries.size(), 13u);
    const BoundarySpec& indenter = scene.boundaries.back();
    EXPECT_EQ(indenter.shape, BoundaryShape::Sphere);
    EXPECT_NEAR(indenter.center.z() - indenter.radius, o.panel.thickness, 1e-12);
    EXPECT_NEAR(indenter.velocity.z(), -o.speed, 1e-12);
    // The central grain's centroid is the block's centre (the shape is symmetric about it).
    EXPECT_NEAR((scene.grains[panel.centralBlock()].pose.position - Vec3(0, 0, 1.5)).norm(), 0.0, 1e-9);

    // For lsdem-run the block is saved and the scene names its file.
    const std::string assetPath = dir.file("block.vdb");
    saveAsset(*block, assetPath);
    scene.assets.front().file = assetPath;
    const std::string path = dir.file("slab_scene.toml");
    writeSlabScene(scene, o, path);
    const Scene back = readSceneFile(path);
    ASSERT_EQ(back.grains.size(), scene.grains.size());
    ASSERT_EQ(back.boundaries.size(), scene.boundaries.size());
    for (size_t k = 0; k < scene.grains.size(); ++k) {
        EXPECT_NEAR((back.grains[k].pose.position - scene.grains[k].pose.position).norm(), 0.0, 1e-12);
        EXPECT_NEAR(back.grains[k].pose.orientation.angularDistance(scene.grains[k].pose.orientation),
                    0.0, 1e-9);
    }
    for (size_t k = 0; k + 1 < scene.boundaries.size(); ++k) {
        EXPECT_EQ(back.boundaries[k].shape, BoundaryShape::LevelSet);
        EXPECT_NEAR((back.boundaries[k].pose.position - scene.boundaries[k].pose.position).norm(), 0.0, 1e-12);
    }
    EXPECT_EQ(back.contacts.front().model.formulation, Formulation::Adapted);
    EXPECT_DOUBLE_EQ(back.contacts.front().model.normalStiffness, slabStiffness(o).knStar);
    EXPECT_DOUBLE_EQ(back.timeStep.fixed, dt);
    EXPECT_EQ(back.end.boundary, 12);
    EXPECT_DOUBLE_EQ(back.end.displacement, 0.3);
}

// A 3×3 coarse panel pushed 0.3 mm: quasi-static (the indenter's force is carried by the frame
// and the blocks' weight, Newton's third law through the contacts) and the central block moves
// more than any other, each of them less than half as far.
TEST(SlabStudy, TinyPanelRunsAndTheCentralBlockMovesMost)
{
    SlabStudyOptions o = tinyOptions();
    const SlabPanel panel(o.panel);
    const auto block = bakeSlabBlock(panel, o.fixedVdp, 1.0);
    const SlabRunResult r = runSlabCase(o, panel, block, Formulation::Adapted, 1.0, o.fixedVdp);
    ASSERT_FALSE(r.stopped) << r.error;
    ASSERT_GE(r.curve.size(), 20u);
    EXPECT_NEAR(r.curve.back().delta, 0.3, 1e-3);
    EXPECT_GT(r.curve.back().force, 0.0);
    const int centre = panel.centralBlock();
    const double drop = -r.finalDisplacement[centre].z();
    EXPECT_GT(drop, 0.2 * 0.3);
    for (size_t k = 0; k < r.finalDisplacement.size(); ++k)
        if (int(k) != centre) {
            EXPECT_LT(r.finalDisplacement[k].norm(), 0.6 * drop) << panel.blocks()[k].name;
        }
    // The P–δ curve rises (the panel resists more the further it is pushed).
    EXPECT_GT(r.curve.back().force, 1.5 * r.curve[r.curve.size() / 2].force);
    // Equilibrium: the frame carries the indenter's push and the blocks' weight, up to the
    // blocks' inertia, small in quasi-static loading.
    const double weight = 9 * o.material.density * block->mass.volume * o.material.gravity;
    for (size_t k = r.curve.size() / 2; k < r.curve.size(); ++k)
        EXPECT_NEAR(r.curve[k].frameForce, r.curve[k].force + weight, 0.05 * r.curve[k].force) << k;
    EXPECT_EQ(r.snapshots.size(), 6u);
    EXPECT_LT(slabFailureSummary(panel, r).find("central block b1_1 moved down"), std::string::npos);
}

// lsdem-study slab as a user runs it, at test size: a two-way study on a 3×3 panel with both
// formulations prints its cost first, then the table and the converged ratio, and writes the
// CSV files, the failure summary, the scene for lsdem-run and (with matplotlib) the plots.
TEST(SlabStudy, ProgramWritesTheStudy)
{
    lsdem::test::ScratchDir dir;
    const std::string out = dir.file("slab");
    const bool matplotlib = runCommand("/usr/bin/python3 -c 'import matplotlib'").exitCode == 0;
    const auto r = runCommand(kStudy + " slab --blocks 3 --sdp 1 0.7 --vdp-fixed 0.3 --vdp 0.6 0.3 "
                                       "--delta-max 0.3 --formulation adapted original --samples 20 "
                                       "--threads 2 --out '" + out + "'");
    ASSERT_EQ(r.exitCode, matplotlib ? 0 : 4) << r.output;
    EXPECT_LT(r.output.find("cost:"), r.output.find("stage 1")) << r.output;
    EXPECT_NE(r.output.find("VDP/SDP ="), std::string::npos) << r.output;
    for (const char* f : {"slab.csv", "slab_runs.csv", "slab_snapshots.csv", "slab_failure.txt",
                          "slab_scene.toml", "slab_block.obj"})
        EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
    // Runs: 2 SDP x 2 formulations, 1 more VDP (0.6) at the chosen SDP, the coarse case.
    std::ifstream runs(out + "/slab_runs.csv");
    int rows = 0;
    for (std::string line; std::getline(runs, line);) rows += !line.empty() && line[0] != '#';
    EXPECT_EQ(rows - 1, 6);
    // The scene reads back (assets relative to its folder).
    const Scene scene = readSceneFile(out + "/slab_scene.toml");
    EXPECT_EQ(scene.grains.size(), 9u);
    if (matplotlib) {
        for (const char* f : {"slab_sdp.png", "slab_vdp.png", "slab_convergence.png", "slab_blocks.png",
                              "slab_snapshots_converged.png"})
            EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
    }
}

TEST(SlabStudy, ProgramRefusesBadInputAndEstimatesWithoutRunning)
{
    lsdem::test::ScratchDir dir;
    auto r = runCommand(kStudy + " slab --blocks 4 --out '" + dir.file("x") + "'");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("--blocks"), std::string::npos) << r.output;
    r = runCommand(kStudy + " slab --vdp-fixed 1.5 --out '" + dir.file("x") + "'");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("4 voxels"), std::string::npos) << r.output;
    r = runCommand(kStudy + " slab --frobnicate");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    r = runCommand(kStudy + " slab --full --estimate --out '" + dir.file("x") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("min on 2 cores"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
}

// Run again into the same folder without plots or scene and at another voxel, the study
// leaves none of the first run's plots, scene, block mesh or baked block (whose
// discretization is not run now); the user's files, named like the study's or not, are kept.
TEST(SlabStudy, ProgramRerunLeavesNoFilesOfTheEarlierRun)
{
    lsdem::test::ScratchDir dir;
    const std::string out = dir.file("slab");
    const std::string tiny = kStudy + " slab --blocks 3 --sdp 1 --no-two-way --formulation "
                                      "adapted --samples 10 --delta-max 0.1 -q --out '" + out + "'";
    const auto first = runCommand(tiny + " --vdp-fixed 0.5");
    const std::string stalePlot = out + "/slab_sdp.png";
    if (first.exitCode == 4) std::ofstream(stalePlot) << "as the first run's plot would be";
    ASSERT_TRUE(std::filesystem::exists(stalePlot)) << first.output;
    for (const char* f : {"slab_scene.toml", "slab_block.obj", "assets/block_sdp1_vdp0.5.vdb"})
        ASSERT_TRUE(std::filesystem::exists(out + "/" + f)) << f << ": " << first.output;
    std::ofstream(out + "/notes.txt") << "the user's";
    std::ofstream(out + "/slab_notes.txt") << "the user's too";
    std::ofstream(out + "/assets/mine.obj") << "the user's mesh";

    const auto second = runCommand(tiny + " --vdp-fixed 0.6 --no-plots --no-scene");
    ASSERT_EQ(second.exitCode, 0) << second.output;
    for (const char* f : {"slab_sdp.png", "slab_scene.toml", "slab_block.obj",
                          "assets/block_sdp1_vdp0.5.vdb"})
        EXPECT_FALSE(std::filesystem::exists(out + "/" + f)) << f << ": " << second.output;
    for (const char* f : {"slab.csv", "slab_runs.csv", "assets/block_sdp1_vdp0.6.vdb",
                          "notes.txt", "slab_notes.txt", "assets/mine.obj"})
        EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
}

// A thread count beyond kMaxThreads (1024) or below 0 (all cores) is refused as bad input
// naming --threads; TBB was asked for 99999999999 threads and the study aborted with
// std::bad_alloc (exit 134).
TEST(SlabStudy, ProgramRefusesAThreadCountOutOfRange)
{
    lsdem::test::ScratchDir dir;
    for (const char* threads : {"99999999999", "1025", "-1", "-2"}) {
        const auto r = runCommand(kStudy + " slab --blocks 3 --sdp 1 --vdp-fixed 0.5 --no-two-way "
                                           "--formulation adapted --samples 10 -q --no-plots "
                                           "--threads " + std::string(threads) + " --out '" +
                                  dir.file("x") + "'");
        EXPECT_EQ(r.exitCode, 1) << threads << ": " << r.output;
        EXPECT_NE(r.output.find("--threads wants 0 (all cores) or a number up to 1024"), std::string::npos)
            << threads << ": " << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
}

// Refining the surface (SDP 0.5 → 0.35 mm, about twice the nodes) on a 3×3 panel pushed
// 0.3 mm: every contact stiffness of the original law grows with the nodes in contact, and
// the panel's response is linear in its contact stiffnesses (displacement control), so P grows
// in proportion to the node count (measured 2.22 for 2.04 times the nodes); the adapted law's P
// barely moves (+3 %: it is converging; the quick study's 5×5 panel changes by 6 % at the same
// step).
TEST(SlabStudy, OriginalGrowsWithTheNodesAdaptedConverges)
{
    SlabStudyOptions o = tinyOptions();
    o.formulations = {Formulation::Adapted, Formulation::Original};
    o.referenceSdp = 0.5;
    const SlabPanel panel(o.panel);
    std::map<Formulation, std::vector<double>> force;
    std::vector<double> nodes;
    for (double sdp : {0.5, 0.35}) {
        const auto block = bakeSlabBlock(panel, 0.1, sdp);
        nodes.push_back(double(block->nodes.size()));
        for (Formulation f : o.formulations) {
            const SlabRunResult r = runSlabCase(o, panel, block, f, sdp, 0.1);
            ASSERT_FALSE(r.stopped) << r.error;
            force[f].push_back(r.curve.back().force);
        }
    }
    const double nodeRatio = nodes[1] / nodes[0];
    EXPECT_NEAR(nodeRatio, 2.0, 0.2);
    EXPECT_NEAR(force[Formulation::Original][1] / force[Formulation::Original][0] / nodeRatio, 1.0, 0.15);
    EXPECT_NEAR(force[Formulation::Adapted][1] / force[Formulation::Adapted][0], 1.0, 0.1);
    // At the reference spacing kn = kn*·(√3/2)·s_ref² makes the two laws agree (a node's
    // area on an equilateral mesh of edge s_ref).
    EXPECT_NEAR(force[Formulation::Original][0] / force[Formulation::Adapted][0], 1.0, 0.05);
}

// Options that are valid one by one but make no study: each refused, naming what to change.
TEST(SlabStudy, OptionsThatMakeNoStudyAreRefused)
{
    struct Case
    {
        const char* what;
        std::function<void(SlabStudyOptions&)> change;
        const char* message;
    };
    const std::vector<Case> cases = {
        {"a formulation twice (its finest run would be compared with itself)",
         [](SlabStudyOptions& o) { o.formulations = {Formulation::Adapted, Formulation::Adapted}; },
         "twice"},
        {"a two-way study without the adapted formulation",
         [](SlabStudyOptions& o) { o.formulations = {Formulation::Original}; }, "adapted"},
        {"an original SDP that stage 1 does not run",
         [](SlabStudyOptions& o) { o.originalSdps = {0.6}; }, "--sdp-original"},
        {"a time step too close to the stability limit",
         [](SlabStudyOptions& o) { o.timeStepSafety = 0.8; }, "--safety"},
        {"an indenter that would take years", [](SlabStudyOptions& o) { o.speed = 1e-6; },
         "time steps"},
        {"voxels that would not fit in memory", [](SlabStudyOptions& o) { o.fixedVdp = 0.002; },
         "GiB"},
    };
    checkSlabStudyOptions(SlabStudyOptions{});  // the defaults are a study
    for (const Case& c : cases) {
        SlabStudyOptions o;
        c.change(o);
        try {
            checkSlabStudyOptions(o);
            ADD_FAILURE() << "accepted: " << c.what;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
                << c.what << ": " << e.what();
        }
    }
}

// The convergence measure on curves whose difference is known exactly: P_a = P_b + c (a
// constant offset) gives c/peak both as the loading-branch RMS and as the peak difference;
// P_a = 1.1·P_b gives a peak difference of 10 %, larger than its RMS; the branch after b's
// peak counts only in the whole-curve measure.
TEST(SlabStudy, CurveDifferenceOfKnownCurves)
{
    std::vector<SlabSample> b, offset, scaled, laterDrop;
    for (int k = 0; k <= 100; ++k) {
        SlabSample s;
        s.delta = 0.02 * k;
        s.force = 1000.0 * std::sin(kPi * s.delta / 2.0);  // peak 1000 N at δ = 1
        b.push_back(s);
        SlabSample u = s;
        u.force = s.force + 50.0;
        offset.push_back(u);
        u.force = 1.1 * s.force;
        scaled.push_back(u);
        u.force = s.delta <= 1.0 ? s.force : 0.0;  // the same up to the peak, then gone
        laterDrop.push_back(u);
    }
    EXPECT_NEAR(slabCurveDifference(b, b), 0.0, 1e-12);
    EXPECT_NEAR(slabCurveDifference(offset, b), 0.05, 1e-12);
    EXPECT_NEAR(slabCurveDifference(scaled, b), 0.1, 1e-12);
    EXPECT_NEAR(slabCurveDifference(laterDrop, b), 0.0, 1e-12);
    // Whole curve: RMS of the lost branch sin(πδ/2) for δ in (1, 2], over all 101 samples.
    double sum = 0.0;
    for (int k = 51; k <= 100; ++k) sum += std::pow(std::sin(kPi * 0.02 * k / 2.0), 2);
    EXPECT_NEAR(slabCurveDifference(laterDrop, b, true), std::sqrt(sum / 101.0), 1e-12);
}

namespace {

/// A synthetic finished run on a 3×3 panel: P = peak·sin(πδ/2) up to δ = 1, and at the end the
/// central block down by centralDrop while every other block moved by othersMoved.
SlabRunResult syntheticRun(const SlabPanel& panel, double peak, double centralDrop, double othersMoved,
                           bool stopped = false)
{
    SlabRunResult r;
    for (int k = 0; k <= 50; ++k) {
        SlabSample s;
        s.delta = 0.02 * k;
        s.force = peak * std::sin(kPi * s.delta / 2.0);
        r.curve.push_back(s);
    }
    for (int b = 0; b < int(panel.blocks().size()); ++b)
        r.finalDisplacement.push_back(b == panel.centralBlock() ? Vec3(0, 0, -centralDrop)
                                                                : Vec3(othersMoved, 0, 0));
    r.stopped = stopped;
    return r;
}

} // namespace

// A run that went unstable ends with blocks at NaN: its summary says so instead of "moved
// down by nan mm", and it has no failure mode.
TEST(SlabStudy, ARunGoneUnstableHasNoFailureMode)
{
    SlabPanelOptions po;
    po.blocksPerSide = 3;
    const SlabPanel panel(po);
    SlabRunResult r = syntheticRun(panel, 1000, 0.8, 0.01, true);
    r.error = "the time step exploded";
    r.finalDisplacement[0].x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(slabFailureMode(panel, r), SlabFailureMode::None);
    const std::string summary = slabFailureSummary(panel, r);
    EXPECT_NE(summary.find("not finite numbers (the run went unstable)"), std::string::npos)
        << summary;
    EXPECT_NE(summary.find("the time step exploded"), std::string::npos) << summary;
    EXPECT_EQ(summary.find("nan"), std::string::npos) << summary;
}

// The convergence rule on runs whose differences and failure modes are set by hand: peaks
// 700, 900, 980, 1000 N differ from the finest by 30, 10, 2 % (tolerance 5 %).
TEST(SlabStudy, ConvergedRunIsTheCoarsestThatAgreesWithTheFinest)
{
    SlabPanelOptions po;
    po.blocksPerSide = 3;
    const SlabPanel panel(po);
    const double pushed = 0.8, still = 0.01;  // δ_max = 1: push-out is a drop over 0.5
    ASSERT_EQ(slabFailureMode(panel, syntheticRun(panel, 1000, pushed, still)), SlabFailureMode::PushOut);
    ASSERT_EQ(slabFailureMode(panel, syntheticRun(panel, 1000, pushed, 1.5)),
              SlabFailureMode::BlocksDisplaced);

    std::vector<SlabRunResult> runs = {syntheticRun(panel, 700, pushed, still),
                                       syntheticRun(panel, 900, pushed, still),
                                       syntheticRun(panel, 980, pushed, still),
                                       syntheticRun(panel, 1000, pushed, still)};
    const std::vector<int> series = {0, 1, 2, 3};
    bool ok = false;
    EXPECT_EQ(slabConvergedRun(panel, runs, series, 0.05, ok), 2);
    EXPECT_TRUE(ok);
    EXPECT_EQ(slabConvergedRun(panel, runs, series, 0.15, ok), 1);  // 10 % now agrees
    EXPECT_TRUE(ok);

    // Within tolerance but failing another way: not converged there, nor coarser.
    runs[2] = syntheticRun(panel, 980, pushed, 1.5);
    EXPECT_EQ(slabConvergedRun(panel, runs, series, 0.15, ok), 3);
    EXPECT_FALSE(ok);

    // A run that stopped early ends the series; a stopped finest run is no reference.
    runs[2] = syntheticRun(panel, 980, pushed, still, /*stopped=*/true);
    EXPECT_EQ(slabConvergedRun(panel, runs, series, 0.15, ok), 3);
    EXPECT_FALSE(ok);
    runs[2] = syntheticRun(panel, 980, pushed, still);
    runs[3].stopped = true;
    EXPECT_EQ(slabConvergedRun(panel, runs, series, 0.15, ok), 3);
    EXPECT_FALSE(ok);

    // The finest alone proves nothing; an empty series has no run.
    runs[3].stopped = false;
    EXPECT_EQ(slabConvergedRun(panel, runs, {3}, 0.05, ok), 3);
    EXPECT_FALSE(ok);
    EXPECT_EQ(slabConvergedRun(panel, runs, {}, 0.05, ok), -1);
    EXPECT_FALSE(ok);
}
