// The 27-sphere stack (tools/studies/Cube27Study): the closed form against its derivation, the
// scene as built, real quasi-static runs against the closed form (adapted) and the growth with
// N (original), and lsdem-study cube27 as a user runs it, bad input included.
#include "studies/Cube27Study.h"

#include "support/TestSupport.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/simulation/World.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

using lsdem::kPi;
using lsdem::test::runCommand;

namespace {

const std::string kStudy = LSDEM_STUDY_EXE;

int countDataLines(const std::string& path)
{
    std::ifstream in(path);
    int n = 0;
    for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
    return n;
}

/// The rows of @a result at the largest δ, per formulation and stiffness.
const lsdem::Cube27Row& lastRow(const lsdem::Cube27Result& result, lsdem::Formulation f,
                                int nodes, double k)
{
    const lsdem::Cube27Row* last = nullptr;
    for (const lsdem::Cube27Row& r : result.rows)
        if (r.formulation == f && r.nodesRequested == nodes && r.stiffness == k &&
            (!last || r.delta > last->delta))
            last = &r;
    if (!last) throw std::runtime_error("no such row");
    return *last;
}

/// A coarse study of law @a f at N = 1000 (voxel 0.15 mm, 50 periods, 2 orientations).
lsdem::Cube27Options coarseStudy(lsdem::Formulation f, std::vector<double> stiffness, int points)
{
    lsdem::Cube27Options o;
    o.formulations = {f};
    o.nodeCounts = {1000};
    o.stiffness = std::move(stiffness);
    o.voxel = 0.15;
    o.periods = 50;
    o.orientations = 2;
    o.points = points;
    o.quiet = true;
    return o;
}

} // namespace

// The closed form restated from its derivation: per column, wall–sphere P = π k R d_w²,
// sphere–sphere P = (π/2) k R d_s², equal forces in series, δ = 2 d_w + 2 d_s.
TEST(Cube27Study, ClosedFormFollowsFromTheColumnInSeries)
{
    const double R = 5.0, k = 1e3, delta = 0.3;
    const double dWall = delta / (2.0 + 2.0 * std::sqrt(2.0));
    const double dSphere = std::sqrt(2.0) * dWall;
    EXPECT_NEAR(kPi * k * R * dWall * dWall, 0.5 * kPi * k * R * dSphere * dSphere, 1e-9);
    EXPECT_NEAR(2 * dWall + 2 * dSphere, delta, 1e-15);
    EXPECT_NEAR(lsdem::cube27ClosedForm(R, delta, k), 9.0 * kPi * k * R * dWall * dWall, 1e-9);
    EXPECT_NEAR(lsdem::cube27ClosedForm(R, delta, k), 545.7497, 1e-3);
    EXPECT_EQ(lsdem::cube27ClosedForm(R, 0.0, k), 0.0);

    // The exact version: every contact of a column carries P/9, and the overlaps add up to δ.
    for (double d : {0.003, 0.03, 0.3, 1.0}) {
        const double P = lsdem::cube27ExactForce(R, d, k);
        const double column = P / 9.0;
        const double w = std::sqrt(column / (kPi * k * R));           // sphere–plane, exact
        const double s = 0.5 * (d - 2.0 * w);                           // the rest: two overlaps
        EXPECT_NEAR(lsdem::exactSphereContactForce(R, s, k) / column, 1.0, 1e-10) << d;
        // Below the parabolic value (the exact sphere–sphere cap is stiffer), converging to it.
        const double ratio = P / lsdem::cube27ClosedForm(R, d, k);
        EXPECT_LT(ratio, 1.0) << d;
        EXPECT_GT(ratio, 1.0 - 0.15 * d / R) << d;
    }
    EXPECT_NEAR(lsdem::cube27ExactForce(R, 0.3, 2e3) / lsdem::cube27ExactForce(R, 0.3, 1e3), 2.0,
                1e-12);

    // The volume law's column: the same sphere–plane force (the wall's normal is the line),
    // its own sphere–sphere integral (stiffer than the adapted one's), so a larger P.
    const auto volume = lsdem::Formulation::Volume;
    for (double d : {0.03, 0.3}) {
        const double P = lsdem::cube27ExactForce(R, d, k, volume);
        const double w = std::sqrt(P / 9.0 / (kPi * k * R));
        const double s = 0.5 * (d - 2.0 * w);
        EXPECT_NEAR(lsdem::exactSphereVolumeForce(R, s, k) / (P / 9.0), 1.0, 1e-10) << d;
        EXPECT_GT(P, lsdem::cube27ExactForce(R, d, k)) << d;
        EXPECT_LT(P, lsdem::cube27ClosedForm(R, d, k)) << d;
    }
}

TEST(Cube27Study, SceneIsAStackJustTouchingTheBox)
{
    lsdem::Cube27Options o;
    o.voxel = 0.2;
    const lsdem::Cube27Run run = lsdem::planCube27Run(o, lsdem::Formulation::Adapted, 300, 1e3, 0);
    const lsdem::Scene scene = lsdem::makeCube27Scene(o, run);
    ASSERT_EQ(scene.grains.size(), 27u);
    ASSERT_EQ(scene.boundaries.size(), 6u);
    EXPECT_EQ(scene.gravity, lsdem::Vec3::Zero());
    EXPECT_EQ(scene.boundaries[1].name, "top");
    EXPECT_NEAR(scene.boundaries[1].velocity.z(), -run.speed, 1e-12);
    for (const lsdem::GrainSpec& a : scene.grains) {
        for (int c = 0; c < 3; ++c) {  // touching the walls or a neighbour on every side
            const double x = a.pose.position[c];
            EXPECT_NEAR(std::fmod(x, 10.0), 5.0, 1e-12);
            EXPECT_GE(x, 5.0);
            EXPECT_LE(x, 25.0);
        }
        EXPECT_NEAR(a.pose.orientation.norm(), 1.0, 1e-12);
    }
    // Orientations differ between grains and between orientation sets.
    EXPECT_GT(scene.grains[0].pose.orientation.angularDistance(scene.grains[1].pose.orientation), 1e-3);
    const lsdem::Scene other =
        lsdem::makeCube27Scene(o, lsdem::planCube27Run(o, lsdem::Formulation::Adapted, 300, 1e3, 1));
    EXPECT_GT(scene.grains[0].pose.orientation.angularDistance(other.grains[0].pose.orientation), 1e-3);

    // Built and evaluated: spheres that only touch feel (almost) nothing at the start.
    std::vector<std::string> warnings;
    lsdem::Simulation sim(lsdem::buildWorld(scene, warnings), run.timeStep);
    for (const lsdem::Grain& g : sim.world().grains) EXPECT_LT(g.force.norm(), 1e-6) << g.name;
    EXPECT_LT(sim.world().boundaries[1].force.norm(), 1e-6);
}

// Found by review: single-node and volume runs got friction 0.3 and ks = kn/2, which they have
// no shear springs for: silently frictionless, and a scene file the reader refuses. Every
// formulation's scene now reads back, with friction only where shear springs carry it.
TEST(Cube27Study, EveryFormulationsSceneReadsBackWithFrictionOnlyOnShearSprings)
{
    lsdem::Cube27Options o;
    o.voxel = 0.2;
    for (lsdem::Formulation f : {lsdem::Formulation::Original, lsdem::Formulation::Adapted,
                                 lsdem::Formulation::SingleNode, lsdem::Formulation::Volume}) {
        const std::string name = lsdem::formulationName(f);
        const lsdem::Cube27Run run = lsdem::planCube27Run(o, f, 300, 1e3, 0);
        const lsdem::Scene written = lsdem::makeCube27Scene(o, run);
        lsdem::Scene read;
        try {
            read = lsdem::parseScene(lsdem::sceneToToml(written, "."), "cube27.toml");
        } catch (const lsdem::Error& e) {
            ADD_FAILURE() << name << ": " << e.what();
            continue;
        }
        const bool shearSprings = f == lsdem::Formulation::Original || f == lsdem::Formulation::Adapted;
        ASSERT_EQ(read.contacts.size(), 2u) << name;
        for (const lsdem::ContactSpec& c : read.contacts) {
            EXPECT_EQ(c.model.friction, shearSprings ? o.friction : 0.0) << name;
            EXPECT_EQ(c.model.shearStiffness, shearSprings ? o.shearRatio * 1e3 : 0.0) << name;
        }
    }
}

// Original and adapted runs are planned dynamically similar: the same number of steps, the
// time step and speed scaled by sqrt of the stiffness ratio, well inside the stability limit.
TEST(Cube27Study, PlanScalesTheLoadingWithTheStiffness)
{
    lsdem::Cube27Options o;
    const lsdem::Cube27Run a = lsdem::planCube27Run(o, lsdem::Formulation::Adapted, 1000, 1e3, 0);
    const lsdem::Cube27Run b = lsdem::planCube27Run(o, lsdem::Formulation::Adapted, 1000, 4e3, 0);
    const lsdem::Cube27Run c = lsdem::planCube27Run(o, lsdem::Formulation::Original, 1000, 1e9, 0);
    EXPECT_EQ(a.steps, b.steps);
    EXPECT_EQ(a.steps, c.steps);
    EXPECT_NEAR(a.timeStep / b.timeStep, 2.0, 1e-9);
    // The original law's kn spread over the 1000 nodes' share of the sphere: kn·N/(4πR²).
    const double kEffective = 1e9 * 1000 / (4 * kPi * 25.0);
    EXPECT_NEAR(a.timeStep / c.timeStep, std::sqrt(kEffective / 1e3), 1e-6 * a.timeStep / c.timeStep);
    EXPECT_NEAR(a.timeStep, o.safety * a.stabilityLimit, 1e-3 * a.timeStep);
    EXPECT_NEAR(a.speed * a.timeStep * a.steps, o.deltaMax, 1e-12);
    // The volume law stiffens like the adapted one without friction (it has no shear springs);
    // it was planned as one linear spring per contact.
    lsdem::Cube27Options frictionless = o;
    frictionless.friction = 0.0;
    const lsdem::Cube27Run v = lsdem::planCube27Run(o, lsdem::Formulation::Volume, 1000, 1e3, 0);
    const lsdem::Cube27Run f =
        lsdem::planCube27Run(frictionless, lsdem::Formulation::Adapted, 1000, 1e3, 0);
    EXPECT_EQ(v.timeStep, f.timeStep);
    EXPECT_EQ(v.steps, f.steps);
    // Explicit steps: too few is refused with the count to use.
    o.steps = 10;
    try {
        lsdem::planCube27Run(o, lsdem::Formulation::Adapted, 1000, 1e3, 0);
        FAIL() << "10 steps accepted";
    } catch (const lsdem::Error& e) {
        EXPECT_NE(std::string(e.what()).find("--steps"), std::string::npos) << e.what();
    }
}

// A coarse adapted study against the continuum closed form. Tolerance 4 % at δ_max: with
// ~1000 nodes a wall cap (radius sqrt(2 R d_w) ≈ 0.8 mm at δ = 0.3 mm) holds only ~10 nodes
// of spacing ~0.55 mm, and over ten orientation sets single runs scattered by -2.6 … +1.1 %
// about the closed form (the level-set gap, ≤ h²/(4R) = 1 µm per sphere contact at voxel
// 0.15 mm, and the dynamics, ~0.2 % at 50 periods, are smaller). The floor reaction must
// equal the top one (quasi-static) and the side walls carry little.
TEST(Cube27Study, CoarseAdaptedRunMatchesTheClosedForm)
{
    const lsdem::Cube27Result result =
        lsdem::runCube27(coarseStudy(lsdem::Formulation::Adapted, {500.0, 1000.0}, 10));
    ASSERT_EQ(result.rows.size(), 2u * 11u);
    const lsdem::Cube27Row& r = lastRow(result, lsdem::Formulation::Adapted, 1000, 1000.0);
    EXPECT_NEAR(r.delta, 0.3, 1e-9);
    EXPECT_NEAR(r.forceExact, lsdem::cube27ExactForce(5.0, 0.3, 1e3), 1e-9);
    EXPECT_NEAR(r.forceMean / r.forceExact, 1.0, 0.04)
        << "P = " << r.forceMean << " N, closed form " << r.forceExact << " N";
    EXPECT_NEAR(r.floorForce / r.forceMean, 1.0, 0.02);
    EXPECT_LT(r.sideForce, 0.1 * r.forceMean);
    // The loading curve follows the closed form over its upper half too.
    for (const lsdem::Cube27Row& row : result.rows)
        if (row.stiffness == 1000.0 && row.delta >= 0.15) {
            EXPECT_NEAR(row.forceMean / row.forceExact, 1.0, 0.08) << "δ = " << row.delta;
        }
    // Linear in kn*: the runs are dynamically similar, so the ratio is nearly exact.
    const lsdem::Cube27Row& half = lastRow(result, lsdem::Formulation::Adapted, 1000, 500.0);
    EXPECT_NEAR(half.forceMean / r.forceMean, 0.5, 0.005);
    for (const lsdem::Cube27Run& run : result.runs)
        EXPECT_GT(run.stabilityLimitSeen, 2.0 * run.timeStep);
}

// The volume law against its own continuum limit (kv times the caps' integral of d); it was
// reported against 9·kv·δ/4, one linear spring per contact (−19.5 % at N = 4000). It has no
// friction, and without friction this coarse assembly comes out below the closed form by 3.0
// to 4.6 % with the volume law and the adapted one alike (measured over 2, 4 and 10
// orientation sets, 2026-11-30): the adapted run above has friction. A change of a level set's
// values by 1e-4 voxel moved that mean by half a percent. So the volume law is held to the
// adapted law without friction on the same orientations (the same nodes' tractions, summed
// along the mean normal instead of each node's: within 1.2 % in those runs; 2 % allowed), and
// to its continuum limit within the frictionless assembly's 6 %.
TEST(Cube27Study, CoarseVolumeRunMatchesItsOwnContinuumLimit)
{
    lsdem::Cube27Options o = coarseStudy(lsdem::Formulation::Volume, {1000.0}, 4);
    o.formulations = {lsdem::Formulation::Volume, lsdem::Formulation::Adapted};
    o.friction = 0.0;
    const lsdem::Cube27Result result = lsdem::runCube27(o);
    const lsdem::Cube27Row& r = lastRow(result, lsdem::Formulation::Volume, 1000, 1000.0);
    const lsdem::Cube27Row& a = lastRow(result, lsdem::Formulation::Adapted, 1000, 1000.0);
    EXPECT_NEAR(r.delta, 0.3, 1e-9);
    EXPECT_NEAR(r.forceExact, lsdem::cube27ExactForce(5.0, 0.3, 1e3, lsdem::Formulation::Volume),
                1e-9);
    EXPECT_NEAR(r.forceClosed, lsdem::cube27ClosedForm(5.0, 0.3, 1e3), 1e-9);
    EXPECT_NEAR(r.forceMean / a.forceMean, 1.0, 0.02)
        << "P = " << r.forceMean << " N, adapted without friction " << a.forceMean << " N";
    EXPECT_NEAR(r.forceMean / r.forceExact, 1.0, 0.06)
        << "P = " << r.forceMean << " N, exact " << r.forceExact << " N";
}

// The original law: P at δ_max grows in proportion to N (by the node count ratio within
// 10 %), and agrees within 10 % with the continuum value of kn·N/(4πR²) uniformly spread.
TEST(Cube27Study, OriginalForceGrowsWithTheNodeCount)
{
    lsdem::Cube27Options o;
    o.formulations = {lsdem::Formulation::Original};
    o.nodeCounts = {400, 1600};
    o.stiffnessFactors = {1.0};
    o.voxel = 0.15;
    o.periods = 30;
    o.points = 5;
    o.quiet = true;
    const lsdem::Cube27Result result = lsdem::runCube27(o);
    const lsdem::Cube27Row& coarse = lastRow(result, lsdem::Formulation::Original, 400, 1e9);
    const lsdem::Cube27Row& fine = lastRow(result, lsdem::Formulation::Original, 1600, 1e9);
    const double nodeRatio = fine.nodesActual / coarse.nodesActual;
    EXPECT_NEAR(nodeRatio, 4.0, 0.2);
    EXPECT_NEAR((fine.forceMean / coarse.forceMean) / nodeRatio, 1.0, 0.10)
        << coarse.forceMean << " N at N = " << coarse.nodesActual << ", " << fine.forceMean
        << " N at N = " << fine.nodesActual;
    EXPECT_NEAR(fine.forceMean / fine.forceExact, 1.0, 0.10);
    // Millions of times the adapted closed form with kn* = 1 GPa/mm: no convergence here.
    EXPECT_GT(fine.forceMean, 1e6 * lsdem::cube27ClosedForm(5.0, 0.3, 1e3));
}

TEST(Cube27Study, ProgramWritesTheCsvAndPlots)
{
    lsdem::test::ScratchDir dir;
    const bool matplotlib = runCommand("/usr/bin/python3 -c 'import matplotlib'").exitCode == 0;
    const auto r = runCommand(kStudy + " cube27 --formulation adapted original --nodes 300"
                              " --k-factors 1 --voxel 0.2 --periods 20 --points 4"
                              " --out " + dir.file("out"));
    // Exit 4: the CSV is complete but plotting was not possible.
    ASSERT_EQ(r.exitCode, matplotlib ? 0 : 4) << r.output;
    EXPECT_NE(r.output.find("node-steps"), std::string::npos) << r.output;  // the cost up front
    EXPECT_NE(r.output.find("time "), std::string::npos) << r.output;
    const std::string csv = dir.file("out/cube27.csv");
    EXPECT_EQ(countDataLines(csv), 1 + 2 * 5);  // header + 2 formulations × (δ = 0 + 4 points)
    std::ifstream in(csv);
    std::string line;
    while (std::getline(in, line) && line[0] == '#') {}
    EXPECT_EQ(line.rfind("formulation,nodes,nodes_actual,kn,voxel,delta,P,", 0), 0u) << line;
    EXPECT_NE(line.find("P_closed"), std::string::npos);
    EXPECT_NE(line.find("P_exact"), std::string::npos);
    if (matplotlib) {
        for (const char* png : {"cube27_fig4b_original_by_nodes.png",
                                "cube27_fig4d_adapted_by_nodes.png", "cube27_convergence.png"}) {
            EXPECT_TRUE(std::filesystem::exists(dir.file("out/") + png)) << png;
        }
    }
}

// Found by review: --delta-max 1e-300 printed P/P_exact as "-nan%" and exited 0. (Its time
// step, 5e144 s, is now refused before the run: the spheres touch at the start.)
TEST(Cube27Study, ARunGoneNonFiniteIsNotReported)
{
    lsdem::test::ScratchDir dir;
    const auto r = runCommand(kStudy + " cube27 --nodes 100 --formulation adapted --voxel 0.5 "
                                       "--k-factors 1 --points 5 --no-plots --delta-max 1e-300 "
                                       "--out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("cube27 run adapted N = 100 k = 1000 orientation 0: the time step "),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("exceeds the stability limit"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("nan%"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out/cube27.csv")));
}

TEST(Cube27Study, ProgramRefusesBadInput)
{
    lsdem::test::ScratchDir dir;
    const std::string out = dir.file("out");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--nodes 0", "--nodes"},
        {"--nodes -100", "--nodes"},
        {"--nodes 300 300", "twice"},
        {"--formulation adapted adapted", "twice"},
        {"--radius 0", "--radius"},
        {"--radius -5", "--radius"},
        {"--delta-max 0", "--delta-max"},
        {"--delta-max -0.1", "--delta-max"},
        {"--delta-max 4", "--delta-max"},
        {"--kn 0", "--kn"},
        {"--kn -1e3", "--kn"},
        {"--voxel nan", "--voxel"},
        {"--voxel 0", "--voxel"},
        {"--speed -1", "--speed"},
        {"--steps 0", "--steps"},
        {"--steps 5 --nodes 300", "--steps"},
        {"--orientations 0", "--orientations"},
        {"--formulation magic", "magic"},
        {"--testing sideways", "sideways"},
        {"--colour red", "--colour"},
        // Found by review: step counts beyond any integer ("give at least --steps
        // -9223372036854775808", a 1-step plan), and plans that would run for years.
        {"--speed 1e-300 --steps 5", "needs at least 8.08205e+306 time steps (the limit is 1e+09)"},
        {"--safety 1e-300", "would take 8.30219e+302 time steps (the limit is 1e+09)"},
        {"--periods 1e300", "needs at least 8.30219e+300 time steps"},
        {"--speed 1e-9", "time steps (the limit is 1e+09)"},
        {"--speed 0.3", "the study would take 2.30499e+09 time steps in its 16 runs"},
        // Found by review: a plan of fewer steps than points (the wall jumping δ_max).
        {"--periods 1e-300", "in 1 time step(s), fewer than the 30 points it records"},
        {"--speed 1e9", "fewer than the 30 points it records"},
        {"--k-factors 1e305", "(--kn, or the paper's times a --k-factors factor) is too stiff"},
    };
    for (const auto& [args, mustSay] : cases) {
        const auto r = runCommand(kStudy + " cube27 " + args + " --no-plots --out " + out);
        EXPECT_EQ(r.exitCode, 1) << args << ": " << r.output;
        EXPECT_NE(r.output.find(mustSay), std::string::npos) << args << ": " << r.output;
        EXPECT_NE(r.output.find("error"), std::string::npos) << args << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;  // nothing made, not even the folder
    }
    // An output folder that cannot be made (a file is in the way), and one not writable.
    std::ofstream(dir.file("blocker")) << "x";
    const auto blocked = runCommand(kStudy + " cube27 --nodes 300 --out " + dir.file("blocker") + "/sub");
    EXPECT_EQ(blocked.exitCode, 1) << blocked.output;
    EXPECT_NE(blocked.output.find("blocker"), std::string::npos) << blocked.output;
    if (::geteuid() != 0) {  // root writes anywhere
        std::filesystem::create_directory(dir.file("locked"));
        std::filesystem::permissions(dir.file("locked"), std::filesystem::perms::owner_read |
                                                              std::filesystem::perms::owner_exec);
        const auto locked = runCommand(kStudy + " cube27 --nodes 300 --out " + dir.file("locked"));
        EXPECT_EQ(locked.exitCode, 1) << locked.output;
        EXPECT_NE(locked.output.find("not writable"), std::string::npos) << locked.output;
        EXPECT_FALSE(std::filesystem::exists(dir.file("locked/cube27.csv")));
        std::filesystem::permissions(dir.file("locked"), std::filesystem::perms::owner_all);
    }
}
