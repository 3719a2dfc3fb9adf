// The triaxial test (tools/studies/TriaxialTest, TriaxialSample, TriaxialStudy) on a small
// sample of the bundled sand grains: the servo walls consolidate it to σ₃ and hold σ₃ on the
// sides while the ends close at the set strain rate; q and p are what the walls' forces over
// their areas say; strains and void ratio follow from the walls' positions and the grains'
// volumes; and the study hands its runs and files over as described.
#include "studies/RunDistributor.h"
#include "studies/TriaxialOutputs.h"
#include "studies/TriaxialSample.h"
#include "studies/TriaxialShearScene.h"
#include "studies/TriaxialStudy.h"
#include "studies/TriaxialTest.h"

#include "support/TestSupport.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/simulation/Simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace lsdem;

namespace {

TriaxialOptions smallOptions()
{
    TriaxialOptions o;
    o.meshes = {std::string(LSDEM_SOURCE_DIR) + "/assets/meshes/sand"};
    o.sdps = {0.15};
    return o;
}

/// The stress the grains put on wall @a b (compression positive), from its force and the
/// positions of the four walls around it: worked out here, apart from TriaxialCell.
double wallStress(const World& w, int wall)
{
    const Boundary& b = w.boundaries[size_t(wall)];
    const int axis = wall / 2;
    double area = 1.0;
    for (int other = 0; other < 3; ++other) {
        if (other == axis) continue;
        const Boundary& low = w.boundaries[size_t(2 * other)];
        const Boundary& high = w.boundaries[size_t(2 * other + 1)];
        area *= (high.plane.point + high.displacement - low.plane.point - low.displacement)[other];
    }
    return -b.force.dot(b.plane.normal) / area;
}

} // namespace

// About a hundred grains, consolidated to 100 kPa and sheared to 3 % axial strain: one run, all
// the checks (a ctest process per test would run it again for each).
TEST(TriaxialTest, HundredGrainsConsolidateHoldSigma3AndReportWallStresses)
{
    TriaxialOptions o = smallOptions();
    o.grains = 100;
    const std::vector<std::string> files = triaxialMeshFiles(o);
    ASSERT_EQ(files.size(), 16u);
    const TriaxialAssets assets = bakeTriaxialAssets(files, o.vdp, o.sdps[0]);
    const TriaxialCloud cloud =
        makeTriaxialCloud(o.grains, int(files.size()), triaxialCloudSpacing(assets), 1);
    std::vector<std::string> warnings;
    World world = buildWorld(triaxialScene(o, assets, cloud, Formulation::Adapted, o.knStar),
                             warnings);
    // No two bounding spheres of the cloud overlap: the lattice keeps them apart.
    for (size_t i = 0; i < world.grains.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            ASSERT_GT((world.grains[i].body.pose.position - world.grains[j].body.pose.position).norm(),
                      world.grains[i].asset->boundingRadius + world.grains[j].asset->boundingRadius);

    TriaxialProtocol p;
    p.confiningStress = o.confiningStress;
    p.strainRate = triaxialStrainRate(o, assets.meanDiameter);
    p.consolidationRate = 10.0 * p.strainRate;
    p.maxAxialStrain = 0.03;
    p.grainDiameter = assets.meanDiameter;
    p.density = o.density;
    p.records = 30;
    Simulation sim(std::move(world), 1.5e-6);
    const TriaxialTestResult r = runTriaxialTest(sim, triaxialWalls(), p);

    // Consolidated: each principal stress within the 2 % tolerance of σ₃.
    ASSERT_TRUE(r.consolidatedWithinTolerance);
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(r.consolidated.stress[axis], p.confiningStress, 0.02 * p.confiningStress);
    EXPECT_GT(r.consolidated.coordination, 3.0);   // a load-bearing packing
    EXPECT_LT(r.consolidated.voidRatio, 1.2);      // far denser than the cloud it came from
    // The grains' own measure of the stress (Love–Weber over the cell's volume) is the walls':
    // in equilibrium the moment of the contact forces is the walls' forces times their
    // distances. It differs by where a wall's contacts act (within its overlap, ~1e-3 of the
    // cell, not on its plane) and by what still moves (consolidated: the kinetic energy is
    // small). Measured: 0.05–0.09 %.
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(r.consolidated.loveWeberStress[axis], r.consolidated.stress[axis],
                    0.01 * p.confiningStress);
    EXPECT_GE(r.consolidated.mechanicalCoordination, r.consolidated.coordination);
    EXPECT_GT(r.consolidated.nodesPerContact, 1.0);

    // The end: the axial strain is ε̇·t of shearing, to within one step of the walls.
    const TriaxialRow& last = r.rows.back();
    ASSERT_EQ(last.stage, 1);
    EXPECT_NEAR(last.axialStrain, p.maxAxialStrain, p.strainRate * sim.timeStep() + 1e-12);
    // q, p and the void ratio from the walls themselves: forces over current areas, volume
    // from their positions, solid volume from the assets.
    const World& w = sim.world();
    double s[3];
    for (int axis = 0; axis < 3; ++axis)
        s[axis] = 0.5 * (wallStress(w, 2 * axis) + wallStress(w, 2 * axis + 1));
    EXPECT_NEAR(last.state.p, (s[0] + s[1] + s[2]) / 3.0, 1e-12 * std::abs(last.state.p));
    EXPECT_NEAR(last.state.q, s[2] - 0.5 * (s[0] + s[1]), 1e-12 * std::abs(last.state.q));
    double solid = 0.0;
    for (const Grain& g : w.grains) solid += g.asset->mass.volume;
    EXPECT_NEAR(last.state.voidRatio, last.state.volume / solid - 1.0, 1e-12);
    EXPECT_NEAR(last.volumetricStrain, 1.0 - last.state.volume / r.consolidated.volume, 1e-12);

    // While shearing, the side walls hold σ₃ within 10 % (a servo of gain 0.5 corrects half
    // its error per step; what is left is the lag behind the sample's dilation), and the sample
    // carries a deviator: a frictional packing under compression.
    for (const TriaxialRow& row : r.rows) {
        if (row.stage != 1 || row.axialStrain < 0.005) continue;
        EXPECT_NEAR(row.state.stress.x(), p.confiningStress, 0.1 * p.confiningStress) << row.step;
        EXPECT_NEAR(row.state.stress.y(), p.confiningStress, 0.1 * p.confiningStress) << row.step;
        EXPECT_GT(row.state.q, 0.0) << row.step;
    }
    // Friction angles of a granular sample with μ = 0.5: between those of a frictionless
    // packing (~5-10°) and the steepest natural sands (~50°).
    EXPECT_GT(r.peakFrictionAngle, 15.0);
    EXPECT_LT(r.peakFrictionAngle, 55.0);
    // The rate makes the inertial number asked for at p = σ₃ (and less once p grows).
    EXPECT_NEAR(r.rows[size_t(std::count_if(r.rows.begin(), r.rows.end(),
                                            [](const TriaxialRow& row) { return row.stage == 0; }))]
                    .inertialNumber,
                o.inertialNumber, 0.05 * o.inertialNumber);
}

namespace {

/// The estimate's plan is each run's own: its nodes, its step and its shearing's steps exactly,
/// unless the step proved unstable while shearing and was halved; then the consolidation was
/// kept, made at the planned step (the consolidation's count is a forecast: TriaxialCost.h).
void expectPlansAreTheRuns(const std::vector<TriaxialRunPlan>& plans, const TriaxialStudyResult& r,
                           long long grains)
{
    ASSERT_EQ(plans.size(), r.runs.size());
    for (size_t k = 0; k < plans.size(); ++k) {
        EXPECT_EQ(plans[k].nodesPerGrain, r.runs[k].nodesPerGrain);
        const double halvings = std::log2(plans[k].timeStep / r.runs[k].dt);
        EXPECT_EQ(halvings, std::round(halvings)) << "run " << k;
        EXPECT_GE(halvings, 0.0) << "run " << k;
        if (halvings == 0.0) {
            EXPECT_EQ(plans[k].shearSteps, r.runs[k].test.shearSteps) << k;
        } else {
            const TriaxialRow& row = r.runs[k].test.rows.front();
            ASSERT_EQ(row.stage, 0);
            EXPECT_NEAR(row.time / double(row.step), plans[k].timeStep, 1e-9 * plans[k].timeStep);
        }
        EXPECT_EQ(plans[k].grains, grains);
        EXPECT_GT(plans[k].startVoidRatio, 1.0) << "the cloud starts loose";
    }
}

} // namespace

// The study: runs in the order formulations × SDPs, original's kn from the coarsest node area,
// the same lattice for every run, and the files with a row per run and per record.
TEST(TriaxialStudy, RunsEachFormulationAtEachSpacingAndWritesItsFiles)
{
    TriaxialOptions o = smallOptions();
    o.grains = 27;
    o.sdps = {0.2, 0.15};
    o.maxAxialStrain = 0.01;
    o.records = 10;
    std::vector<TriaxialRunPlan> plans;
    const TriaxialStudyResult r = runTriaxialStudy(
        o, serialRunDistributor(), {}, {},
        [&](const std::vector<TriaxialRunPlan>& p) { plans = p; });
    ASSERT_EQ(r.runs.size(), 4u);
    expectPlansAreTheRuns(plans, r, 27);
    EXPECT_EQ(r.runs[0].formulation, Formulation::Adapted);
    EXPECT_EQ(r.runs[1].sdp, 0.15);
    EXPECT_EQ(r.runs[2].formulation, Formulation::Original);
    const TriaxialAssets coarsest = bakeTriaxialAssets(triaxialMeshFiles(o), o.vdp, 0.2);
    EXPECT_DOUBLE_EQ(r.runs[2].stiffness, o.knStar * coarsest.meanNodeArea);
    EXPECT_DOUBLE_EQ(r.spacing, triaxialCloudSpacing(coarsest));
    EXPECT_GT(r.runs[1].nodesPerGrain, 1.5 * r.runs[0].nodesPerGrain);  // (0.2/0.15)² = 1.8
    for (const TriaxialRun& run : r.runs) {
        EXPECT_TRUE(run.test.consolidatedWithinTolerance);
        EXPECT_NEAR(run.test.rows.back().axialStrain, 0.01, 1e-4);
        // What comes from the contacts survives the runs' records (packed for the ranks).
        const TriaxialState& end = run.test.rows.back().state;
        EXPECT_GT(end.nodesPerContact, 1.0);
        EXPECT_GT(end.mechanicalCoordination, 0.0);
        // (27 grains sheared fast: only roughly the walls' stress; a consolidated sample
        // agrees to 0.1 %, TriaxialTest.HundredGrains…)
        EXPECT_NEAR(end.loveWeberStress.x(), end.stress.x(), 0.2 * end.stress.x());
        EXPECT_GT(run.test.consolidated.nodesPerContact, 1.0);
    }

    const std::string dir = ::testing::TempDir() + "/triaxial_study";
    std::filesystem::create_directories(dir);
    writeTriaxialCsv(r, dir + "/triaxial.csv");
    writeTriaxialRunsCsv(r, dir + "/triaxial_runs.csv");
    auto lines = [](const std::string& path) {
        std::ifstream in(path);
        std::string line;
        size_t n = 0;
        while (std::getline(in, line)) ++n;
        return n;
    };
    size_t rows = 0;
    for (const TriaxialRun& run : r.runs) rows += run.test.rows.size();
    EXPECT_EQ(lines(dir + "/triaxial.csv"), rows + 1);
    EXPECT_EQ(lines(dir + "/triaxial_runs.csv"), r.runs.size() + 1);
    EXPECT_TRUE(std::isfinite(finestPeakChange(r, Formulation::Adapted)));

    // The shearing as a scene for lsdem-run: read back, it holds the consolidated sample, the
    // side walls at σ₃ and the ends closing at the run's rate until the axial strain.
    const TriaxialRun& finest = r.runs[1];
    const Scene scene = readSceneFile(writeTriaxialShearScene(o, r, finest, dir + "/scene"));
    ASSERT_EQ(scene.grains.size(), 27u);
    for (size_t k = 0; k < scene.grains.size(); ++k)
        EXPECT_LT((scene.grains[k].pose.position - finest.test.consolidatedPoses[k].position).norm(), 1e-12);
    ASSERT_EQ(scene.boundaries.size(), 6u);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(scene.boundaries[size_t(k)].servo.targetStress, o.confiningStress);
        EXPECT_TRUE(scene.boundaries[size_t(k)].servo.areaFromWalls());
    }
    const double height = finest.test.consolidated.size.z();
    EXPECT_NEAR(scene.boundaries[5].velocity.z(), -0.5 * finest.strainRate * height, 1e-12);
    EXPECT_EQ(scene.end.boundary, 5);
    EXPECT_NEAR(scene.end.displacement, 0.5 * o.maxAxialStrain * height, 1e-12);
    // The run's step, or less: a margin under the least stable step the run met.
    EXPECT_GT(scene.timeStep.fixed, 0.0);
    EXPECT_LE(scene.timeStep.fixed, finest.dt);
    EXPECT_LE(scene.timeStep.fixed, kShearSceneStepOverLimit * finest.stabilityLimit * (1 + 1e-12));
}

TEST(TriaxialOptions, BadValuesNameTheOption)
{
    auto message = [](TriaxialOptions o) {
        try {
            checkTriaxialOptions(o);
            triaxialMeshFiles(o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    TriaxialOptions o = smallOptions();
    EXPECT_EQ(message(o), "accepted");
    TriaxialOptions up = o;
    up.sdps = {0.05, 0.1};
    EXPECT_NE(message(up).find("--sdps must be decreasing"), std::string::npos);
    TriaxialOptions tension = o;
    tension.confiningStress = -0.1;
    EXPECT_NE(message(tension).find("--confining-stress"), std::string::npos);
    TriaxialOptions noSeed = o;
    noSeed.seeds = {};
    EXPECT_NE(message(noSeed).find("--seed needs at least one seed"), std::string::npos);
    TriaxialOptions negativeSeed = o;
    negativeSeed.seeds = {1, -2};
    EXPECT_NE(message(negativeSeed).find("--seed wants numbers >= 0, got -2"), std::string::npos);
    TriaxialOptions seedTwice = o;
    seedTwice.seeds = {3, 1, 3};
    EXPECT_NE(message(seedTwice).find("--seed 3 is given twice"), std::string::npos);
    TriaxialOptions few = o;
    few.grains = 3;
    EXPECT_NE(message(few).find("--grains"), std::string::npos);
    TriaxialOptions single = o;
    single.formulations = {Formulation::SingleNode};
    EXPECT_NE(message(single).find("original and adapted"), std::string::npos);
    // A cylinder in a membrane has one lateral stress; undrained it keeps its volume instead.
    TriaxialOptions membraneTrue = o;
    membraneTrue.membrane = true;
    membraneTrue.path = TriaxialPath::TrueTriaxial;
    EXPECT_NE(message(membraneTrue).find("cannot follow --path true-triaxial"), std::string::npos);
    TriaxialOptions membraneUndrained = membraneTrue;
    membraneUndrained.path = TriaxialPath::Undrained;
    EXPECT_EQ(message(membraneUndrained), "accepted");
    TriaxialOptions noScene = o;
    noScene.sceneStrain = 0.2;
    noScene.path = TriaxialPath::Undrained;
    EXPECT_NE(message(noScene).find("--scene-strain is for the shear scene"), std::string::npos);
    TriaxialOptions flat = o;
    flat.heightRatio = 0.1;
    EXPECT_NE(message(flat).find("--height-ratio must be from 0.25 to 4, got 0.1"),
              std::string::npos);
    TriaxialOptions missing = o;
    missing.meshes = {"/nonexistent/sand"};
    EXPECT_NE(message(missing).find("/nonexistent/sand"), std::string::npos);
    // Found by review: these ran out of memory (exit 3).
    TriaxialOptions threads = o;
    threads.threads = 99999999999;
    EXPECT_NE(message(threads).find("--threads wants 0 (all cores) or a number up to 1024, got 99999999999"),
              std::string::npos)
        << message(threads);
    TriaxialOptions many = o;
    many.grains = 100000000000;
    EXPECT_NE(message(many).find("--grains 100000000000 is over the limit of a scene (1000000)"),
              std::string::npos)
        << message(many);
    // A mesh given twice, by a folder and by name: one asset written over the other.
    TriaxialOptions twice = o;
    const std::string folder = o.meshes.front();
    twice.meshes = {folder, folder + "/grain_0003.obj"};
    EXPECT_NE(message(twice).find("gives this mesh twice: as part of the folder " + folder +
                                  " and as " + folder + "/grain_0003.obj"),
              std::string::npos)
        << message(twice);
}

// Several seeds: each is a sample of its own on the same lattice, every formulation and SDP is
// run on each (seeds innermost), a run is the one a study of its seed alone makes, and the
// summary's means and spreads are those of the runs.
TEST(TriaxialStudy, EachSeedIsASampleAndTheSummaryTakesTheirMeans)
{
    TriaxialOptions o = smallOptions();
    o.grains = 27;
    o.sdps = {0.2, 0.15};
    o.formulations = {Formulation::Adapted};
    o.seeds = {1, 2};
    o.maxAxialStrain = 0.01;
    o.records = 10;
    std::vector<TriaxialRunPlan> plans;
    const TriaxialStudyResult r = runTriaxialStudy(
        o, serialRunDistributor(), {}, {},
        [&](const std::vector<TriaxialRunPlan>& p) { plans = p; });
    ASSERT_EQ(r.runs.size(), 4u);
    expectPlansAreTheRuns(plans, r, 27);
    const double sdps[4] = {0.2, 0.2, 0.15, 0.15};
    const long long seeds[4] = {1, 2, 1, 2};
    for (size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(r.runs[k].sdp, sdps[k]) << k;
        EXPECT_EQ(r.runs[k].seed, seeds[k]) << k;
    }
    // Two samples: the same lattice, other meshes and orientations, so another packing.
    EXPECT_NE(r.runs[0].test.consolidated.voidRatio, r.runs[1].test.consolidated.voidRatio);
    EXPECT_NE(r.runs[0].test.consolidatedPoses[0].orientation.coeffs(),
              r.runs[1].test.consolidatedPoses[0].orientation.coeffs());

    // Seed 2 at SDP 0.2 is the run a study of seed 2 alone makes, number for number.
    TriaxialOptions alone = o;
    alone.sdps = {0.2};
    alone.seeds = {2};
    const TriaxialStudyResult single = runTriaxialStudy(alone, serialRunDistributor());
    ASSERT_EQ(single.runs.size(), 1u);
    EXPECT_EQ(single.spacing, r.spacing);
    EXPECT_EQ(single.runs[0].seed, 2);
    EXPECT_EQ(single.runs[0].test.peakFrictionAngle, r.runs[1].test.peakFrictionAngle);
    EXPECT_EQ(single.runs[0].test.secantModulus50, r.runs[1].test.secantModulus50);
    EXPECT_EQ(single.runs[0].test.shearSteps, r.runs[1].test.shearSteps);

    // The means: of two samples a and b, (a + b)/2 and the spread |a − b|/√2.
    const std::vector<TriaxialSeedMean> means = triaxialSeedMeans(r);
    ASSERT_EQ(means.size(), 2u);
    for (size_t m = 0; m < 2; ++m) {
        const TriaxialTestResult& a = r.runs[2 * m].test;
        const TriaxialTestResult& b = r.runs[2 * m + 1].test;
        EXPECT_EQ(means[m].sdp, sdps[2 * m]);
        EXPECT_EQ(means[m].seeds, 2);
        EXPECT_NEAR(means[m].peakFrictionAngle, 0.5 * (a.peakFrictionAngle + b.peakFrictionAngle),
                    1e-12);
        EXPECT_NEAR(means[m].peakFrictionAngleSpread,
                    std::abs(a.peakFrictionAngle - b.peakFrictionAngle) / std::sqrt(2.0), 1e-12);
        EXPECT_NEAR(means[m].secantModulus50, 0.5 * (a.secantModulus50 + b.secantModulus50),
                    1e-12 * a.secantModulus50);
        EXPECT_NEAR(means[m].secantModulus50Spread,
                    std::abs(a.secantModulus50 - b.secantModulus50) / std::sqrt(2.0),
                    1e-12 * a.secantModulus50);
    }
    EXPECT_NEAR(finestPeakChange(r, Formulation::Adapted),
                means[1].peakFrictionAngle - means[0].peakFrictionAngle, 1e-12);
    EXPECT_NEAR(finestModulusChange(r, Formulation::Adapted),
                means[1].secantModulus50 / means[0].secantModulus50 - 1.0, 1e-12);
    // One seed has no spread.
    EXPECT_TRUE(std::isnan(triaxialSeedMeans(single)[0].peakFrictionAngleSpread));

    // Both files name each row's seed.
    const std::string dir = ::testing::TempDir() + "/triaxial_seeds";
    std::filesystem::create_directories(dir);
    writeTriaxialCsv(r, dir + "/triaxial.csv");
    writeTriaxialRunsCsv(r, dir + "/triaxial_runs.csv");
    std::ifstream runs(dir + "/triaxial_runs.csv");
    std::string header, line;
    std::getline(runs, header);
    EXPECT_EQ(header.rfind("formulation,sdp,seed,", 0), 0u) << header;
    for (size_t k = 0; k < 4; ++k) {
        ASSERT_TRUE(std::getline(runs, line));
        std::istringstream fields(line);
        std::string formulation, sdp, seed;
        std::getline(fields, formulation, ',');
        std::getline(fields, sdp, ',');
        std::getline(fields, seed, ',');
        EXPECT_EQ(seed, std::to_string(seeds[k])) << line;
    }
    std::ifstream rows(dir + "/triaxial.csv");
    std::getline(rows, header);
    EXPECT_EQ(header.rfind("formulation,sdp,seed,", 0), 0u) << header;
}

// Found by review: two meshes of one file name (from two folders) were two [assets.g] of the
// shear scene and one assets/g.vdb. Each keeps its stem if no other file has it.
TEST(TriaxialSample, MeshesOfOneStemGetDistinctNames)
{
    EXPECT_EQ(triaxialAssetNames({"a/g.obj", "b/g.stl", "c/g_2.obj", "h.obj", "d/g.off"}),
              (std::vector<std::string>{"g", "g_3", "g_2", "h", "g_4"}));
}

// The starting lattice: a cube by default; with a height ratio, a prism that tall over its
// width as near as whole sites allow (10,000 grains at 2: 17 × 17 sites, 35 layers).
TEST(TriaxialSample, TheLatticeIsAsTallAsAsked)
{
    const TriaxialCloud cube = makeTriaxialCloud(1000, 3, 1.0, 1);
    EXPECT_EQ(cube.boxMax, Vec3(10, 10, 10));
    const TriaxialCloud tall = makeTriaxialCloud(10000, 3, 1.0, 1, 2.0);
    EXPECT_EQ(tall.boxMax, Vec3(17, 17, 35));
    EXPECT_EQ(tall.pose.size(), 10000u);
    for (const RigidPose& p : tall.pose)
        EXPECT_TRUE((p.position.array() > 0.0).all() && (p.position.array() < tall.boxMax.array()).all());
    const TriaxialCloud squat = makeTriaxialCloud(1000, 3, 1.0, 1, 0.5);
    EXPECT_EQ(squat.boxMax, Vec3(12, 12, 7));  // 12² · 7 = 1008 sites: 7 · 12 ≈ 0.58 of the width
}

// Found by review: a tiny strain rate or time step gave a step count beyond any integer (0
// shearing steps, exit 0), and --inertial-number 1e-9 a run of years.
TEST(TriaxialTest, ShearingStepsAreCountedOrRefused)
{
    TriaxialProtocol p;
    p.maxAxialStrain = 0.2;
    p.strainRate = 1.0;
    EXPECT_EQ(triaxialShearSteps(p, 1e-3), 200);
    auto refusal = [&](double rate, double dt) {
        p.strainRate = rate;
        try {
            triaxialShearSteps(p, dt);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(refusal(1e-300, 1e-3).find("the shearing would take 2e+302 time steps"),
              std::string::npos);
    EXPECT_NE(refusal(1.0, 1e-300).find("--inertial-number"), std::string::npos);
    EXPECT_NE(refusal(1.0, 1e-10).find("(the limit is 1e+09)"), std::string::npos);
    EXPECT_NE(refusal(1.0, 0.0).find("inf time steps"), std::string::npos);
    EXPECT_NE(refusal(INFINITY, 1e-3).find("0 time steps"), std::string::npos);
}

namespace {

const std::string kStudy = LSDEM_STUDY_EXE;

/// lsdem-study triaxial on a few grains of @a meshes, to 1 % axial strain, adapted only (a
/// run that does not end in two minutes fails).
test::CommandResult smallTriaxial(const std::string& meshes, const std::string& out,
                                  const std::string& more = "")
{
    return test::runCommand("timeout 120 " + kStudy + " triaxial --meshes " + meshes +
                            " --grains 8 --sdps 0.2 --formulation adapted --axial-strain 0.01 "
                            "--records 2 --no-plots --quiet --out " + out + " " + more);
}

} // namespace

// Refused before the output folder is made. Found by review: out of memory (exit 3) for the
// first two, and a shear scene with one asset written over the other for the last two.
TEST(TriaxialStudy, ProgramRefusesBadInputBeforeAnyWork)
{
    test::ScratchDir dir;
    const std::string sand = std::string(LSDEM_SOURCE_DIR) + "/assets/meshes/sand";
    const std::string grain = sand + "/grain_0000.obj";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--threads 99999999999", "--threads wants 0 (all cores) or a number up to 1024"},
        {"--grains 100000000000", "over the limit of a scene"},
        {"--seed 2 1 2", "--seed 2 is given twice"},
        {"--seed 1 x", "--seed"},
        {sand + " " + grain, "gives this mesh twice"},
        {grain + " " + sand + "/../sand/grain_0000.obj", "gives this mesh twice"},
    };
    for (const auto& [args, mustSay] : cases) {
        // A small study if accepted after all, so that the test fails rather than runs on.
        const test::CommandResult r = args[0] == '-' ? smallTriaxial(grain, dir.file("out"), args)
                                                     : smallTriaxial(args, dir.file("out"));
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(mustSay), std::string::npos) << args << "\n" << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << args;
    }
}

TEST(TriaxialStudy, MeshesOfOneFileNameAreTwoAssetsOfTheShearScene)
{
    test::ScratchDir dir;
    const std::string sand = std::string(LSDEM_SOURCE_DIR) + "/assets/meshes/sand";
    std::filesystem::create_directories(dir.file("m1"));
    std::filesystem::create_directories(dir.file("m2"));
    std::filesystem::copy_file(sand + "/grain_0000.obj", dir.file("m1/g.obj"));
    std::filesystem::copy_file(sand + "/grain_0001.obj", dir.file("m2/g.obj"));
    const test::CommandResult r =
        smallTriaxial(dir.file("m1/g.obj") + " " + dir.file("m2/g.obj"), dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Scene scene = readSceneFile(dir.file("out/scene/triaxial_shear.toml"));
    ASSERT_EQ(scene.assets.size(), 2u);
    EXPECT_EQ(scene.assets[0].name, "g");
    EXPECT_EQ(scene.assets[1].name, "g_2");
    // Each its own file, baked from its own mesh.
    EXPECT_EQ(scene.assets[0].file, dir.file("out/scene/assets/g.vdb"));
    EXPECT_EQ(scene.assets[1].file, dir.file("out/scene/assets/g_2.vdb"));
    EXPECT_NE(test::readFile(scene.assets[0].file), test::readFile(scene.assets[1].file));

    // Run again with another mesh: the assets the earlier scene named go, a file of the
    // user's beside them stays (review finding: every .vdb there was removed).
    std::ofstream(dir.file("out/scene/assets/mine.vdb")) << "the user's";
    const test::CommandResult again = smallTriaxial(sand + "/grain_0002.obj", dir.file("out"));
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out/scene/assets/g.vdb")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("out/scene/assets/g_2.vdb")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/scene/assets/grain_0002.vdb")));
    EXPECT_EQ(test::readFile(dir.file("out/scene/assets/mine.vdb")), "the user's");
}

// Refused once the time step is known (after the bake), before the consolidation. Found by
// review: --inertial-number 1e-9 ran on for years; --confining-stress 1e300 reported a negative
// void ratio with exit 0.
TEST(TriaxialStudy, ProgramRefusesARunTooLongOrGoneNonPhysical)
{
    test::ScratchDir dir;
    const std::string grain = std::string(LSDEM_SOURCE_DIR) + "/assets/meshes/sand/grain_0000.obj";
    const test::CommandResult slow =
        smallTriaxial(grain, dir.file("slow"), "--axial-strain 0.2 --inertial-number 1e-9");
    EXPECT_EQ(slow.exitCode, 1) << slow.output;
    EXPECT_NE(slow.output.find("the shearing would take 1.38e+10 time steps"), std::string::npos)
        << slow.output;
    const test::CommandResult crushed =
        smallTriaxial(grain, dir.file("crushed"), "--confining-stress 1e300");
    EXPECT_EQ(crushed.exitCode, 1) << crushed.output;
    EXPECT_NE(crushed.output.find("the triaxial run of adapted at SDP 0.2 mm became impossible"),
              std::string::npos)
        << crushed.output;
    EXPECT_NE(crushed.output.find("check the scales and units"), std::string::npos)
        << crushed.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("crushed/triaxial.csv")));
}

// Peak, critical state and E₅₀ of a made-up curve with known answers: q rises linearly with
// slope E to its peak at 2 %, then falls to a plateau; rows every 0.3 % (E₅₀ falls between
// rows, so the interpolation is what finds it).
TEST(TriaxialSummary, PeakCriticalStateAndSecantModulusOfAKnownCurve)
{
    const double E = 50.0, sigma3 = 0.1;
    TriaxialTestResult r;
    for (int k = 0; k <= 60; ++k) {
        TriaxialRow row;
        row.stage = 1;
        row.axialStrain = 0.003 * k;
        const double eps = row.axialStrain;
        row.state.q = eps <= 0.02 ? E * eps : std::max(0.6, E * 0.02 - 10.0 * (eps - 0.02));
        row.state.stress = Vec3(sigma3, sigma3, sigma3 + row.state.q);
        row.state.voidRatio = 0.5 + eps;
        row.frictionAngle = mobilisedFrictionAngle(row.state);
        r.rows.push_back(row);
    }
    summariseTriaxialShearing(r, 0.18);
    EXPECT_NEAR(r.secantModulus50, E, 1e-9 * E);
    // Peak: the highest row, 2.1 % (q = 1 − 10·0.001 = 0.99; 1.8 % has only 0.9), where
    // sin φ = q / (q + 2σ₃).
    EXPECT_NEAR(r.peakAxialStrain, 0.021, 1e-12);
    EXPECT_NEAR(r.peakFrictionAngle, std::asin(0.99 / 1.19) * 180.0 / kPi, 1e-9);
    // Critical state: the plateau q = 0.6 over the last quarter (ε ≥ 13.5 %).
    EXPECT_NEAR(r.criticalFrictionAngle, std::asin(0.6 / 0.8) * 180.0 / kPi, 1e-9);
}

// Successive SDPs compared seed by seed. Three seeds whose peak angles rise by 1.0, 1.2 and 1.4°
// from SDP 0.1 to 0.07 although the seeds themselves spread by 5°: the paired change is 1.2° with
// a standard deviation of 0.2 and a standard error of 0.2/√3 (the difference of the means would
// carry the seeds' 5° spread). E₅₀ 10, 20, 40 MPa becoming 11, 22, 40: +10 %, +10 %, 0 %. A seed
// run at one SDP only is left out; the nodes per contact are the paired runs' means.
TEST(TriaxialSummary, SuccessiveSpacingsArePairedSeedBySeed)
{
    TriaxialStudyResult r;
    const auto add = [&](double sdp, long long seed, double phi, double modulus, double nodes) {
        TriaxialRun run;
        run.formulation = Formulation::Adapted;
        run.sdp = sdp;
        run.seed = seed;
        run.test.peakFrictionAngle = phi;
        run.test.secantModulus50 = modulus;
        run.test.consolidated.nodesPerContact = nodes;
        r.runs.push_back(run);
    };
    add(0.1, 1, 30.0, 10.0, 2.0);
    add(0.1, 2, 35.0, 20.0, 2.5);
    add(0.1, 3, 40.0, 40.0, 3.0);
    add(0.1, 4, 99.0, 99.0, 9.0);  // not run at 0.07
    add(0.07, 1, 31.0, 11.0, 4.0);
    add(0.07, 2, 36.2, 22.0, 5.0);
    add(0.07, 3, 41.4, 40.0, 6.0);
    const std::vector<TriaxialPairedChange> changes = triaxialPairedChanges(r);
    ASSERT_EQ(changes.size(), 1u);
    const TriaxialPairedChange& c = changes[0];
    EXPECT_EQ(c.coarseSdp, 0.1);
    EXPECT_EQ(c.fineSdp, 0.07);
    EXPECT_EQ(c.seeds, 3);
    EXPECT_NEAR(c.peakFrictionAngle, 1.2, 1e-12);
    EXPECT_NEAR(c.peakFrictionAngleSpread, 0.2, 1e-12);
    EXPECT_NEAR(c.peakFrictionAngleError, 0.2 / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(c.secantModulus50, 0.2 / 3.0, 1e-12);
    // sd of (0.1, 0.1, 0): sqrt(((1/30)² · 2 + (2/30)²) / 2) = sqrt(6/900 / 2) = 1/√300
    EXPECT_NEAR(c.secantModulus50Spread, 1.0 / std::sqrt(300.0), 1e-12);
    EXPECT_NEAR(c.coarseNodesPerContact, 2.5, 1e-12);
    EXPECT_NEAR(c.fineNodesPerContact, 5.0, 1e-12);

    // One seed: the change, and no spread.
    r.runs = {r.runs[0], r.runs[4]};
    const TriaxialPairedChange one = triaxialPairedChanges(r).at(0);
    EXPECT_NEAR(one.peakFrictionAngle, 1.0, 1e-12);
    EXPECT_TRUE(std::isnan(one.peakFrictionAngleError));
}

// On a periodic cell the shear scene is a periodic scene: no walls, the cell as consolidated
// (the grains inside it), x and y at σ₃ by stress control, z strained at the run's rate, to the
// end strain's time; lsdem-run builds its world.
TEST(TriaxialStudy, APeriodicRunWritesAPeriodicShearScene)
{
    test::ScratchDir dir;
    const test::CommandResult r = test::runCommand(
        "timeout 120 " + kStudy + " triaxial --meshes " + std::string(LSDEM_SOURCE_DIR) +
        "/assets/meshes/sand --grains 250 --sdps 0.2 --formulation adapted --axial-strain 0.005 "
        "--records 2 --boundary periodic --height-ratio 2 --scene-strain 0.2 --no-plots --quiet "
        "--out " + dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Scene scene = readSceneFile(dir.file("out/scene/triaxial_shear.toml"));
    EXPECT_TRUE(scene.boundaries.empty());
    EXPECT_GT(scene.periodicCell.minCoeff(), 0.0);
    // A tall sample (5 x 5 sites, 10 layers: twice as tall, consolidated alike).
    EXPECT_NEAR(scene.periodicCell.z() / scene.periodicCell.x(), 2.0, 0.2);
    EXPECT_EQ(scene.periodicStress, Vec3(0.1, 0.1, 0.0));
    EXPECT_LT(scene.periodicStrainRate.z(), 0.0);
    // To 20 % (not the run's 0.5 %): the height H0·e^(−ε̇t) is 0.8 H0 at the end.
    EXPECT_NEAR(std::exp(scene.periodicStrainRate.z() * scene.end.time), 0.8, 1e-12);
    EXPECT_NEAR(scene.output.vtkPeriod, scene.end.time / 20.0, 1e-15);
    EXPECT_TRUE(scene.output.micromechanics);
    EXPECT_GT(scene.output.frameSpacing, 0.2);  // a quarter of the sand's 1 mm
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    EXPECT_EQ(w.grains.size(), 250u);
    for (const Grain& g : w.grains)
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(g.body.pose.position[a], w.periodic.origin[a]);
            EXPECT_LT(g.body.pose.position[a], w.periodic.origin[a] + w.periodic.size[a]);
        }
}

// A membrane run writes its shearing as a scene too: the cylinder's grains, the two platens
// closing, and the membrane placed as consolidation left it (a state file) over the tube it
// was made as. Built and stepped, the membrane holds every grain. Fails if the scene kept the
// side walls or the whole sample, or the membrane were put back as the undeformed tube.
TEST(TriaxialStudy, AMembraneRunWritesAMembraneShearScene)
{
    test::ScratchDir dir;
    const test::CommandResult r = test::runCommand(
        "timeout 240 " + kStudy + " triaxial --meshes " + std::string(LSDEM_SOURCE_DIR) +
        "/assets/meshes/sand --grains 150 --sdps 0.2 --formulation adapted --axial-strain 0.002 "
        "--records 2 --boundary membrane --no-plots --out " + dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const size_t round = r.output.rfind("membrane round ");  // (the last try)
    ASSERT_NE(round, std::string::npos) << r.output;
    const size_t kept = std::stoul(r.output.substr(round + 15));
    EXPECT_NE(r.output.find("out/scene/triaxial_shear.toml"), std::string::npos) << r.output;
    const Scene scene = readSceneFile(dir.file("out/scene/triaxial_shear.toml"));
    ASSERT_EQ(scene.grainFiles.size(), 1u);
    EXPECT_EQ(scene.grainFiles[0].count, kept);
    ASSERT_EQ(scene.boundaries.size(), 2u);  // the platens
    EXPECT_GT(scene.boundaries[0].velocity.z(), 0.0);
    EXPECT_LT(scene.boundaries[1].velocity.z(), 0.0);
    EXPECT_EQ(scene.end.boundary, 1);
    ASSERT_EQ(scene.membranes.size(), 1u);
    const MembraneSpec& spec = scene.membranes[0];
    EXPECT_EQ(spec.hold, (std::vector<int>{0, 1}));
    EXPECT_FALSE(spec.state.empty());
    EXPECT_GT(spec.pressure, 0.0);
    EXPECT_GT(spec.drag, 0.0);
    EXPECT_EQ(spec.prestretch, 1.05);
    EXPECT_EQ(spec.rubber.youngs, 1.4);  // --membrane-youngs's default
    std::vector<std::string> warnings;
    World w = buildWorld(scene, warnings);
    ASSERT_EQ(w.grains.size(), kept);
    const Membrane& m = w.membranes[0];
    // The tube and its mass scaling as the run made them ("…, N triangles, its mass R times
    // the grains'", R to 3 digits).
    const std::string made = r.output.substr(round, r.output.find('\n', round) - round);
    const size_t triangles = std::stoul(made.substr(made.rfind(", ", made.find(" triangles")) + 2));
    EXPECT_EQ(m.triangles.size(), triangles) << made;
    EXPECT_EQ(size_t(2 * spec.segments * spec.rings), triangles);
    double membraneMass = 0.0, grainMass = 0.0;
    for (double mass : m.masses) membraneMass += mass;
    for (const Grain& g : w.grains) grainMass += g.body.mass;
    const double ratio = std::stod(made.substr(made.find("its mass ") + 9));
    EXPECT_NEAR(membraneMass / grainMass, ratio, 0.005 * ratio) << made;
    // Placed as consolidation left it: no longer the tube as made (radius times 1 at every
    // vertex), its rims still on the platens.
    double furthest = 0.0;
    for (const Vec3& x : m.positions)
        furthest = std::max(furthest, std::abs(std::hypot(x.x() - spec.base.x(), x.y() - spec.base.y()) - spec.radius));
    EXPECT_GT(furthest, 1e-3 * spec.radius);
    const double bottom = scene.boundaries[0].point.z(), top = scene.boundaries[1].point.z();
    for (size_t v = 0; v < m.positions.size(); ++v) {
        if (m.heldBy[v] < 0) continue;
        EXPECT_NEAR(m.positions[v].z(), m.heldBy[v] == 0 ? bottom : top, 1e-9 * (top - bottom));
    }
    // It encloses the consolidated sample: the grains fill 1/(1 + e₀) of its volume, e₀ the
    // void ratio the run measured in its membrane (the tube as made would enclose them at
    // under a third), and they press on it from the start.
    std::ifstream runs(dir.file("out/triaxial_runs.csv"));
    std::string header, row;
    ASSERT_TRUE(std::getline(runs, header) && std::getline(runs, row));
    const auto field = [](const std::string& line, size_t k) {
        std::stringstream in(line);
        std::string f;
        for (size_t i = 0; i <= k; ++i) std::getline(in, f, ',');
        return f;
    };
    size_t column = 0;
    while (field(header, column) != "void_ratio_0") ASSERT_LT(++column, 100u) << header;
    const double e0 = std::stod(field(row, column));
    double solid = 0.0;
    for (const Grain& g : w.grains) solid += g.asset->mass.volume;
    EXPECT_NEAR(solid / enclosedVolume(m), 1.0 / (1.0 + e0), 1e-6);
    EXPECT_LT(solid / (kPi * spec.radius * spec.radius * spec.height), 1.0 / 3.0);
    Simulation sim(std::move(w), scene.timeStep.fixed);
    for (int k = 0; k < 50; ++k) sim.step();
    Vec3 push = Vec3::Zero();
    for (const Vec3& f : sim.world().membranes[0].grainForces) push += f.cwiseAbs();
    EXPECT_GT(push.x() + push.y(), 0.0);
}
