// Checkpoints: a run stopped, saved, restored into a freshly built world and continued ends in
// the same bits as a run that never stopped; damaged or foreign files are refused with an Error
// naming them, and a failed restore leaves the world as it was.
#include "lsdem/run/Checkpoint.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <type_traits>

using namespace lsdem;

namespace {

constexpr double kRadius = 5.0;  // mm; units mm, N, s, tonne
constexpr double kDt = 2e-6;     // s: ~1/200 of the stiffest impact's contact period here

/// A sphere asset of @a radius (~2000 nodes, voxel 0.25 mm) saved to @a path.
void saveSphere(double radius, const std::string& path)
{
    BakeOptions o;
    o.voxelSize = 0.25;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = 2000;
    std::vector<std::string> warnings;
    saveAsset(bakeAnalytic(AnalyticShape::sphere(radius), o, warnings), path);
}

/// A sphere asset (R = 5 mm), baked once for this file.
const std::string& sphereFile()
{
    static lsdem::test::ScratchDir dir;
    static const std::string path = [] {
        const std::string p = dir.file("sphere.vdb");
        saveSphere(kRadius, p);
        return p;
    }();
    return path;
}

/// @a side³ steel spheres on a loose lattice (gaps of 0.01 mm) with random velocities and spins,
/// under gravity, on a floor with friction, pushed by a side wall moving in +x: grain pairs and
/// grain–floor contacts slide (non-empty shear history) and the moving wall does work.
Scene stackScene(int side)
{
    Scene s;
    AssetSpec a;
    a.name = "sphere";
    a.file = sphereFile();
    s.assets.push_back(a);
    MaterialSpec steel;
    steel.name = "steel";
    steel.density = 7.85e-9;
    s.materials.push_back(steel);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = 1e3;
    c.model.shearStiffness = 500.0;
    c.model.friction = 0.4;
    c.model.damping = ViscousDamping(0.5);
    s.contacts.push_back(c);
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> n;
    const double pitch = 2.0 * kRadius + 0.01;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            for (int k = 0; k < side; ++k) {
                GrainSpec g;
                g.pose.position = Vec3(pitch * i + 0.3 * u(rng), pitch * j + 0.3 * u(rng),
                                       kRadius + 0.005 + pitch * k);
                g.pose.orientation = Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
                g.velocity = Vec3(100.0 * u(rng), 100.0 * u(rng), -100.0 + 100.0 * u(rng));
                g.angularVelocity = Vec3(20.0 * u(rng), 20.0 * u(rng), 20.0 * u(rng));
                s.grains.push_back(g);
            }
    BoundarySpec floor;
    floor.name = "floor";
    s.boundaries.push_back(floor);
    BoundarySpec wall;
    wall.name = "pusher";
    wall.point = Vec3(-kRadius - 0.3, 0, 0);
    wall.normal = Vec3::UnitX();
    wall.velocity = Vec3(150.0, 0, 0);
    s.boundaries.push_back(wall);
    s.gravity = Vec3(0, 0, -9810.0);
    return s;
}

World build(const Scene& scene)
{
    std::vector<std::string> warnings;
    return buildWorld(scene, warnings);
}

template <typename T> bool sameBits(const T& a, const T& b)
{
    static_assert(std::is_arithmetic_v<T>, "compare numbers bit for bit; give other types their own");
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool sameBits(const Vec3& a, const Vec3& b)
{
    return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

bool sameBits(const Quat& a, const Quat& b)
{
    return sameBits(a.w(), b.w()) && sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) &&
           sameBits(a.z(), b.z());
}

bool sameBits(const ShearHistory& a, const ShearHistory& b)
{
    if (a.size() != b.size()) return false;
    for (size_t k = 0; k < a.size(); ++k)
        if (a.entries()[k].node != b.entries()[k].node ||
            !sameBits(a.entries()[k].force, b.entries()[k].force) ||
            std::memcmp(&a.entries()[k].stiffness, &b.entries()[k].stiffness, sizeof(double)) != 0)
            return false;
    return true;
}

/// Everything a checkpoint holds about the world, compared bit for bit.
void expectSameState(const World& a, const World& b)
{
    EXPECT_TRUE(sameBits(a.time, b.time));
    EXPECT_EQ(a.step, b.step);
    EXPECT_TRUE(sameBits(a.energy.boundaryWork, b.energy.boundaryWork));
    EXPECT_TRUE(sameBits(a.energy.initialTotal, b.energy.initialTotal));
    ASSERT_EQ(a.grains.size(), b.grains.size());
    for (size_t i = 0; i < a.grains.size(); ++i) {
        const Grain& x = a.grains[i];
        const Grain& y = b.grains[i];
        EXPECT_TRUE(sameBits(x.body.pose.position, y.body.pose.position)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.body.pose.orientation, y.body.pose.orientation)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.body.velocity, y.body.velocity)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.body.angularMomentum, y.body.angularMomentum)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.force, y.force)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.torque, y.torque)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.dissipated.friction, y.dissipated.friction)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.dissipated.dashpot, y.dissipated.dashpot)) << "grain " << i;
        EXPECT_TRUE(sameBits(x.dissipated.globalDamping, y.dissipated.globalDamping)) << i;
    }
    ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
    for (size_t k = 0; k < a.boundaries.size(); ++k) {
        EXPECT_TRUE(sameBits(a.boundaries[k].displacement, b.boundaries[k].displacement)) << k;
        EXPECT_TRUE(sameBits(a.boundaries[k].force, b.boundaries[k].force)) << k;
        EXPECT_TRUE(sameBits(a.boundaries[k].normalStiffness, b.boundaries[k].normalStiffness));
        EXPECT_TRUE(sameBits(a.boundaries[k].normalDashpot, b.boundaries[k].normalDashpot));
    }
    // The histories that hold shear (empty ones are the contact list's bookkeeping).
    std::vector<std::pair<std::pair<int, int>, const PairHistory*>> pairsA, pairsB;
    for (const auto& [key, h] : a.pairHistory)
        if (!h.empty()) pairsA.emplace_back(key, &h);
    for (const auto& [key, h] : b.pairHistory)
        if (!h.empty()) pairsB.emplace_back(key, &h);
    ASSERT_EQ(pairsA.size(), pairsB.size());
    for (size_t k = 0; k < pairsA.size(); ++k) {
        EXPECT_EQ(pairsA[k].first, pairsB[k].first);
        EXPECT_TRUE(sameBits(pairsA[k].second->shearOnFirstNodes, pairsB[k].second->shearOnFirstNodes));
        EXPECT_TRUE(sameBits(pairsA[k].second->shearOnSecondNodes, pairsB[k].second->shearOnSecondNodes));
    }
    std::vector<std::pair<std::pair<int, int>, const ShearHistory*>> wallsA, wallsB;
    for (const auto& [key, h] : a.boundaryHistory)
        if (!h.empty()) wallsA.emplace_back(key, &h);
    for (const auto& [key, h] : b.boundaryHistory)
        if (!h.empty()) wallsB.emplace_back(key, &h);
    ASSERT_EQ(wallsA.size(), wallsB.size());
    for (size_t k = 0; k < wallsA.size(); ++k) {
        EXPECT_EQ(wallsA[k].first, wallsB[k].first);
        EXPECT_TRUE(sameBits(*wallsA[k].second, *wallsB[k].second));
    }
}

size_t shearedPairs(const World& w)
{
    size_t n = 0;
    for (const auto& [pair, h] : w.pairHistory) n += h.empty() ? 0 : 1;
    return n;
}

size_t shearedBoundaryContacts(const World& w)
{
    size_t n = 0;
    for (const auto& [key, h] : w.boundaryHistory) n += h.empty() ? 0 : 1;
    return n;
}

std::string readBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

Checkpoint sampleHeader()
{
    Checkpoint c;
    c.scenePath = "/somewhere/stack.toml";
    c.sceneText = "# the scene\n[simulation]\ntime_step = 2e-6\n";
    c.timeStep = kDt;
    c.record.energyRows = {{0.0, 0.0, 1.5}, {10.0, 2e-5, 1.25}};
    c.record.boundaryRows = {{{0.0, 1.0}}, {{0.0, 2.0}, {10.0, 3.0}}};
    c.record.vtkFrameTimes = {0.0, 1e-4};
    c.record.micromechanicsRows = {{0.0, 0.0, -2.5}, {10.0, 2e-5, -2.25}};
    return c;
}

/// A world stepped a little, with contacts and shear, to restore into.
World steppedWorld(int steps)
{
    Simulation sim(build(stackScene(2)), kDt);
    for (int k = 0; k < steps; ++k) sim.step();
    return sim.world();
}

} // namespace

// N steps straight against N/2 steps, a checkpoint, a fresh world built from the same scene with
// the checkpoint restored into it (no force evaluation: the forces come from the file), and N/2
// more steps: the same bits everywhere, shear history included.
// The stack again in a cell periodic along x and y, compressed along x: the checkpoint carries
// the cell as the run left it and the periods each grain was moved by.
TEST(Checkpoint, ADeformingPeriodicCellRestartsBitIdentically)
{
    const int n = 300;
    Scene scene = stackScene(2);
    const double pitch = 2.0 * kRadius + 0.01;
    scene.periodicCell = Vec3(2.3 * pitch, 2.3 * pitch, 0.0);  // at least 4.5 radii
    scene.periodicOrigin = Vec3(-0.5 * pitch, -0.5 * pitch, 0.0);
    scene.periodicStrainRate = Vec3(-2.0, 0.0, 0.0);
    Simulation straight(build(scene), kDt);
    for (int k = 0; k < n; ++k) straight.step();
    Simulation first(build(scene), kDt);
    for (int k = 0; k < n / 2; ++k) first.step();
    ASSERT_NE(first.world().periodic.size.x(), scene.periodicCell.x());
    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("run.lsdem");
    saveCheckpoint(path, first.world(), sampleHeader());
    World fresh = build(scene);
    restoreWorldState(path, fresh);
    expectSameState(fresh, first.world());
    EXPECT_TRUE(sameBits(fresh.periodic.size, first.world().periodic.size));
    Simulation second(std::move(fresh), kDt, /*evaluateInitialForces=*/false);
    for (int k = 0; k < n / 2; ++k) second.step();
    expectSameState(second.world(), straight.world());
    EXPECT_TRUE(sameBits(second.world().periodic.size, straight.world().periodic.size));
    bool wrapped = false;
    for (size_t i = 0; i < straight.world().grains.size(); ++i) {
        EXPECT_TRUE(sameBits(second.world().grains[i].wrapShift, straight.world().grains[i].wrapShift));
        wrapped |= !straight.world().grains[i].wrapShift.isZero(0.0);
    }
    EXPECT_TRUE(sameBits(straight.energies().boundaryWork, second.energies().boundaryWork));
    // A scene whose cell is periodic along other axes is refused.
    Scene other = scene;
    other.periodicCell = Vec3(2.3 * pitch, 0.0, 0.0);
    other.periodicStrainRate = Vec3(-2.0, 0.0, 0.0);
    World mismatched = build(other);
    EXPECT_THROW(restoreWorldState(path, mismatched), Error);
    std::printf("[ measured ] periodic restart: %s grain wrapped through a face\n",
                wrapped ? "a" : "no");
}

TEST(Checkpoint, RestartContinuesBitIdentically)
{
    const int n = 300;
    const Scene scene = stackScene(2);

    Simulation straight(build(scene), kDt);
    for (int k = 0; k < n; ++k) straight.step();

    Simulation first(build(scene), kDt);
    for (int k = 0; k < n / 2; ++k) first.step();
    // The state to carry over is not trivial: contacts slide, the pusher has done work.
    ASSERT_GT(shearedPairs(first.world()), 0u);
    ASSERT_GT(shearedBoundaryContacts(first.world()), 0u);
    ASSERT_NE(first.world().energy.boundaryWork, 0.0);

    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("run.lsdem");
    const Checkpoint header = sampleHeader();
    saveCheckpoint(path, first.world(), header);
    EXPECT_EQ(dir.entryCount(), 1u);  // written atomically: no temporary left

    // The header comes back as written.
    const Checkpoint back = readCheckpoint(path);
    EXPECT_EQ(back.scenePath, header.scenePath);
    EXPECT_EQ(back.sceneText, header.sceneText);
    EXPECT_TRUE(sameBits(back.timeStep, header.timeStep));
    EXPECT_EQ(back.record.energyRows, header.record.energyRows);
    EXPECT_EQ(back.record.boundaryRows, header.record.boundaryRows);
    EXPECT_EQ(back.record.vtkFrameTimes, header.record.vtkFrameTimes);
    EXPECT_EQ(back.record.micromechanicsRows, header.record.micromechanicsRows);

    World fresh = build(scene);
    restoreWorldState(path, fresh);
    expectSameState(fresh, first.world());

    Simulation second(std::move(fresh), kDt, /*evaluateInitialForces=*/false);
    for (int k = 0; k < n / 2; ++k) second.step();
    expectSameState(second.world(), straight.world());
    EXPECT_GT(shearedPairs(second.world()), 0u);

    const Energies a = straight.energies(), b = second.energies();
    EXPECT_TRUE(sameBits(a.kinetic, b.kinetic));
    EXPECT_TRUE(sameBits(a.elastic, b.elastic));
    EXPECT_TRUE(sameBits(a.potential, b.potential));
    EXPECT_TRUE(sameBits(a.boundaryWork, b.boundaryWork));
    EXPECT_TRUE(sameBits(a.dissipated, b.dissipated));
}

// The rows and the state come from one reading of the file: replaced after readCheckpoint (by
// a run still writing its folder), the state restored is still the one its rows go with.
// Split over ranks, the others parse rank 0's bytes: the same checkpoint.
TEST(Checkpoint, TheStateComesFromTheReadingOfTheRows)
{
    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("run.lsdem");
    const World early = steppedWorld(10);
    saveCheckpoint(path, early, sampleHeader());
    const Checkpoint read = readCheckpoint(path);
    Checkpoint laterHeader = sampleHeader();
    laterHeader.record.energyRows.push_back({150.0, 3e-4, 1.0});
    saveCheckpoint(path, steppedWorld(150), laterHeader);

    World w = build(stackScene(2));
    restoreWorldState(read, path, w);
    expectSameState(w, early);
    EXPECT_EQ(read.record.energyRows, sampleHeader().record.energyRows);
    const Checkpoint parsed = parseCheckpoint(read.fileBytes, path);
    EXPECT_EQ(parsed.record.energyRows, sampleHeader().record.energyRows);
    World fromParsed = build(stackScene(2));
    restoreWorldState(parsed, path, fromParsed);
    expectSameState(fromParsed, early);
}

// A lid keeping a stress on the stack (a servo wall: its velocity follows from its force, its
// contact stiffness and the walls' positions, so its stiffness is part of the checkpoint): cut,
// restored and continued, it moves exactly as in the run that never stopped.
TEST(Checkpoint, ServoWallRestartContinuesBitIdentically)
{
    const int n = 300;
    Scene scene = stackScene(2);
    BoundarySpec lid;
    lid.name = "lid";
    lid.point = Vec3(0, 0, 4.0 * kRadius);  // 0.015 mm into the top spheres
    lid.normal = -Vec3::UnitZ();
    lid.servo.targetStress = 0.04;  // 16 N over 400 mm², about what it starts with
    lid.servo.area = 400.0;
    lid.servo.maxSpeed = 1000.0;  // so the proportional law, not the limit, sets its speed
    scene.boundaries.push_back(lid);

    Simulation straight(build(scene), kDt);
    for (int k = 0; k < n; ++k) straight.step();
    Simulation first(build(scene), kDt);
    for (int k = 0; k < n / 2; ++k) first.step();
    const Boundary& moving = first.world().boundaries.back();
    ASSERT_GT(moving.normalStiffness, 0.0);  // pressing on the stack, under servo control
    ASSERT_GT(moving.normalDashpot, 0.0);    // (the contacts are damped: restitution 0.5)
    ASSERT_NE(moving.velocity.z(), 0.0);
    ASSERT_LT(moving.velocity.norm(), lid.servo.maxSpeed);

    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("run.lsdem");
    saveCheckpoint(path, first.world(), sampleHeader());
    World fresh = build(scene);
    restoreWorldState(path, fresh);
    expectSameState(fresh, first.world());
    Simulation second(std::move(fresh), kDt, /*evaluateInitialForces=*/false);
    for (int k = 0; k < n / 2; ++k) second.step();
    expectSameState(second.world(), straight.world());
    EXPECT_TRUE(sameBits(second.world().boundaries.back().velocity,
                         straight.world().boundaries.back().velocity));
    EXPECT_NE(straight.world().boundaries.back().velocity, moving.velocity);
}

// A checkpoint cut anywhere (inside the magic, inside the header, in the middle of the grains,
// one byte short of the trailer) is refused with an Error naming the file, and the world handed
// to restoreWorldState is left exactly as it was.
TEST(Checkpoint, TruncatedFileIsRefusedAndTheWorldIsUnchanged)
{
    lsdem::test::ScratchDir dir;
    const std::string good = dir.file("good.lsdem");
    saveCheckpoint(good, steppedWorld(150), sampleHeader());
    const std::string bytes = readBytes(good);
    ASSERT_GT(bytes.size(), 1000u);

    const World before = steppedWorld(40);
    ASSERT_GT(before.boundaryHistory.size(), 0u);
    for (size_t cut : {size_t(0), size_t(5), size_t(30), bytes.size() / 2, bytes.size() - 1}) {
        const std::string path = dir.file("cut" + std::to_string(cut) + ".lsdem");
        writeBytes(path, bytes.substr(0, cut));
        World w = before;
        try {
            restoreWorldState(path, w);
            ADD_FAILURE() << "a checkpoint cut at " << cut << " bytes was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path) << e.what();
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
        }
        expectSameState(w, before);
        if (cut < 100) {  // the header itself is cut
            EXPECT_THROW(readCheckpoint(path), Error) << cut;
        }
    }
}

// A file that is not a checkpoint, a missing file, and a checkpoint of another scene (a
// different number of grains): each refused with an Error naming the file, the world unchanged.
TEST(Checkpoint, ForeignMissingAndMismatchedFilesAreRefused)
{
    lsdem::test::ScratchDir dir;
    const World before = steppedWorld(40);

    const std::string text = dir.file("notes.lsdem");
    writeBytes(text, "this is not a checkpoint, just some text that is long enough\n");
    const std::string missing = dir.file("missing.lsdem");
    const std::string other = dir.file("other.lsdem");
    {
        Simulation small(build(stackScene(1)), kDt);
        small.step();
        saveCheckpoint(other, small.world(), sampleHeader());
    }
    for (const std::string& path : {text, missing, other}) {
        World w = before;
        try {
            restoreWorldState(path, w);
            ADD_FAILURE() << path << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path) << e.what();
        }
        expectSameState(w, before);
    }
    try {
        readCheckpoint(text);
        ADD_FAILURE() << "a text file was read as a checkpoint";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), text);
        EXPECT_NE(e.problem().find("not an lsdem checkpoint"), std::string::npos) << e.what();
    }
}

// A checkpoint whose bytes were damaged so that a count reads as huge (here the number of energy
// rows, 2⁴⁰ − 1) is refused with the same Error as a truncated one: a count can never exceed
// what the rest of the file could hold, so nothing is allocated for it.
TEST(Checkpoint, CorruptCountIsRefusedWithoutAllocatingForIt)
{
    lsdem::test::ScratchDir dir;
    const std::string good = dir.file("good.lsdem");
    const Checkpoint header = sampleHeader();
    saveCheckpoint(good, steppedWorld(10), header);
    std::string bytes = readBytes(good);
    // magic, version, scene path, scene text, time step, then the count of energy rows.
    const size_t at = 8 + 4 + 8 + header.scenePath.size() + 8 + header.sceneText.size() + 8;
    uint64_t count = 0;
    std::memcpy(&count, bytes.data() + at, sizeof count);
    ASSERT_EQ(count, header.record.energyRows.size());
    for (uint64_t huge : {(uint64_t(1) << 40) - 1, uint64_t(1) << 20}) {
        std::memcpy(bytes.data() + at, &huge, sizeof huge);
        const std::string path = dir.file("corrupt.lsdem");
        writeBytes(path, bytes);
        World w = steppedWorld(0);
        const World before = w;
        try {
            restoreWorldState(path, w);
            ADD_FAILURE() << "a corrupt count was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not an lsdem::Error: " << e.what();
        }
        expectSameState(w, before);
        EXPECT_THROW(readCheckpoint(path), Error);
    }
}

// A checkpoint whose shear histories name grains or boundaries the scene does not have (a
// damaged file) is refused, and the world is left as it was: such an index would be read
// past the world's arrays.
TEST(Checkpoint, HistoriesOfGrainsOrBoundariesNotInTheSceneAreRefused)
{
    lsdem::test::ScratchDir dir;
    const World stepped = steppedWorld(10);
    ASSERT_GT(stepped.grains.size(), 1u);
    const int grains = static_cast<int>(stepped.grains.size());
    const int boundaries = static_cast<int>(stepped.boundaries.size());
    ShearHistory shear;
    shear.append(0, Vec3(1.0, 0.0, 0.0));
    PairHistory sheared;
    sheared.shearOnFirstNodes = shear;
    int index = 0;
    auto withPair = [&](int i, int j) {
        World w = stepped;
        w.pairHistory[{i, j}] = sheared;
        return w;
    };
    auto withBoundaryContact = [&](int i, int b) {
        World w = stepped;
        w.boundaryHistory[{i, b}] = shear;
        return w;
    };
    for (const World& bad : {withPair(0, grains), withPair(-1, 1), withPair(1, 1),
                             withPair(1, 0), withBoundaryContact(grains, 0),
                             withBoundaryContact(0, boundaries), withBoundaryContact(0, -1)}) {
        const std::string path = dir.file("bad" + std::to_string(index++) + ".lsdem");
        saveCheckpoint(path, bad, sampleHeader());
        World w = steppedWorld(0);
        const World before = w;
        EXPECT_THROW(restoreWorldState(path, w), Error) << path;
        expectSameState(w, before);
    }
    // The same with indices inside the scene reads back.
    const std::string good = dir.file("good.lsdem");
    saveCheckpoint(good, withPair(0, grains - 1), sampleHeader());
    World w = steppedWorld(0);
    restoreWorldState(good, w);
    EXPECT_TRUE(sameBits(w.pairHistory.at({0, grains - 1}).shearOnFirstNodes, shear));
}

// A state that no run could have saved (a NaN or an infinity in a grain's or boundary's
// numbers or in a shear force, a rotation that is not one, a negative step) is refused as
// damaged, the world unchanged: a restart must not start from it.
TEST(Checkpoint, NonFiniteOrImpossibleStateIsRefused)
{
    lsdem::test::ScratchDir dir;
    const World stepped = steppedWorld(10);
    ASSERT_FALSE(stepped.boundaries.empty());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<World> bad(7, stepped);
    bad[0].grains[0].body.pose.position.y() = nan;
    bad[1].grains[1].body.velocity.z() = inf;
    bad[2].grains[0].torque.x() = -inf;
    bad[3].grains[0].body.pose.orientation = Quat(2.0, 0.0, 0.0, 0.0);  // not a rotation
    bad[4].boundaries[0].force.x() = nan;
    bad[5].step = -1;
    ShearHistory shear;
    shear.append(0, Vec3(nan, 0.0, 0.0));
    bad[6].boundaryHistory[{0, 0}] = shear;
    for (size_t k = 0; k < bad.size(); ++k) {
        const std::string path = dir.file("impossible" + std::to_string(k) + ".lsdem");
        saveCheckpoint(path, bad[k], sampleHeader());
        World w = steppedWorld(0);
        const World before = w;
        try {
            restoreWorldState(path, w);
            ADD_FAILURE() << "case " << k << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("truncated or corrupt"), std::string::npos) << k;
        }
        expectSameState(w, before);
    }
    // The state it was made from restores.
    const std::string good = dir.file("possible.lsdem");
    saveCheckpoint(good, stepped, sampleHeader());
    World w = steppedWorld(0);
    restoreWorldState(good, w);
    expectSameState(w, stepped);
}

// A restart reads the scene from the checkpoint but its asset and grain files as they are
// then. A world rebuilt from a changed asset file, or with a grain renamed or of another
// mass (as an edited grain file would give), is refused, naming the grain or boundary; the
// world rebuilt from the same files, or with an asset more that nothing uses, restores
// (RestartContinuesBitIdentically covers the rest).
TEST(Checkpoint, ARestartFromChangedAssetsOrGrainsIsRefused)
{
    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("c.lsdem");
    Checkpoint plain = sampleHeader();  // (no micromechanics rows: see format 4 below)
    plain.record.micromechanicsRows.clear();
    saveCheckpoint(path, steppedWorld(10), plain);
    auto refusal = [&](World w) {
        const World before = w;
        try {
            restoreWorldState(path, w);
        } catch (const Error& e) {
            expectSameState(w, before);
            EXPECT_EQ(e.where(), path);
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(refusal(build(stackScene(2))), "");

    // The asset file replaced by a slightly larger sphere.
    const std::string larger = dir.file("larger.vdb");
    saveSphere(1.01 * kRadius, larger);
    Scene changed = stackScene(2);
    changed.assets[0].file = larger;
    const std::string asset = refusal(build(changed));
    EXPECT_NE(asset.find("grain 0 ('grain0'): its asset is not the one the run was checkpointed "
                         "with"),
              std::string::npos)
        << asset;
    // An asset no grain uses (a folder of assets grown since) does not matter.
    Scene grown = stackScene(2);
    grown.assets.push_back(changed.assets[0]);
    grown.assets.back().name = "unused";
    EXPECT_EQ(refusal(build(grown)), "");
    // A boundary that now has a level set it did not have.
    World obstacle = build(stackScene(2));
    obstacle.boundaries[0].asset = obstacle.grains[0].asset;
    EXPECT_NE(refusal(obstacle).find("boundary 'floor': its level set"), std::string::npos);
    // A checkpoint of format 4 (before the slope bound took only φ ≥ 0, 2026-11-27) has asset
    // fingerprints of the earlier bound: its assets are not compared (the boundary's new level
    // set passes), its grains still are.
    {
        // Format 4 had no micromechanics rows (format 6 put their count after the frame times)
        // and no periodic cell nor dissipated energies or periods per grain (format 7 put the
        // cell's four vectors after the energies and six numbers after each grain's torque): a
        // checkpoint saved with marker values there (seen nowhere else) loses them. Nor had it
        // membranes (format 8 put their rows' count after the micromechanics rows and their
        // count after the boundaries, here after a marked dashpot), nor a cell's rows (format
        // 9 put their count after the membranes' rows), nor its shear springs' stiffness
        // (format 10 put it after each spring's force).
        World marked = steppedWorld(10);
        const double markedStiffness = 9.0625e5;
        auto markStiffness = [&](ShearHistory& h) {
            ShearHistory again;
            for (const ShearHistory::Entry& e : h.entries())
                again.append(e.node, e.force, markedStiffness);
            h = again;
        };
        for (auto& [ids, h] : marked.pairHistory) {
            markStiffness(h.shearOnFirstNodes);
            markStiffness(h.shearOnSecondNodes);
        }
        for (auto& [ids, h] : marked.boundaryHistory) markStiffness(h);
        for (size_t i = 0; i < marked.grains.size(); ++i)
            marked.grains[i].dissipated = {1e5 + double(i), 2e5, 3e5};
        const Vec3 markedCell(7.25e5, 7.5e5, 7.75e5);  // format 7's cell size, also cut out
        marked.periodic.size = markedCell;
        const double markedDashpot = 8.125e5;
        marked.boundaries.back().normalDashpot = markedDashpot;
        Checkpoint markedHeader = plain;
        const double marker = 12345.678901;
        markedHeader.record.micromechanicsRows = {{marker}};
        saveCheckpoint(dir.file("marked.lsdem"), marked, markedHeader);
        std::string bytes = readBytes(dir.file("marked.lsdem"));
        const auto find = [&](double value) {
            return bytes.find(std::string(reinterpret_cast<const char*>(&value), sizeof value));
        };
        int springs = 0;
        for (size_t at = find(markedStiffness); at != std::string::npos;
             at = find(markedStiffness), ++springs)
            bytes.erase(at, sizeof(double));
        EXPECT_GT(springs, 0);
        const size_t dashpotAt = find(markedDashpot);
        ASSERT_NE(dashpotAt, std::string::npos);
        bytes.erase(dashpotAt + sizeof(double), sizeof(uint64_t));  // no membranes
        for (size_t i = marked.grains.size(); i-- > 0;) {
            const size_t at = find(1e5 + double(i));
            ASSERT_NE(at, std::string::npos);
            bytes.erase(at, 6 * sizeof(double));
        }
        const size_t cellAt = find(markedCell.x());
        ASSERT_NE(cellAt, std::string::npos);
        bytes.erase(cellAt, 12 * sizeof(double));  // its size, strain rate, stress, moment
        const size_t at = find(marker);
        ASSERT_NE(at, std::string::npos);
        // The rows' count, the row's count, the row, no membranes' rows, no cell rows.
        bytes.erase(at - 16, 40);
        const uint32_t four = 4;
        std::memcpy(bytes.data() + 8, &four, sizeof four);  // after the magic
        const std::string older = dir.file("format4.lsdem");
        writeBytes(older, bytes);
        World w = obstacle;
        EXPECT_NO_THROW(restoreWorldState(older, w));
        // Its grains restart with nothing dissipated, and its energy rows' split is unknown.
        for (const Grain& g : w.grains) EXPECT_EQ(g.dissipated.friction + g.dissipated.dashpot, 0.0);
        const Checkpoint olderHeader = readCheckpoint(older);
        ASSERT_EQ(olderHeader.record.energyRows.size(), plain.record.energyRows.size());
        for (size_t k = 0; k < plain.record.energyRows.size(); ++k) {
            const std::vector<double>& row = olderHeader.record.energyRows[k];
            ASSERT_EQ(row.size(), plain.record.energyRows[k].size() + 3);
            EXPECT_TRUE(std::isnan(row.back()));
        }
        World renamedToo = obstacle;
        renamedToo.grains[3].name = "other";
        EXPECT_THROW(restoreWorldState(older, renamedToo), Error);
    }

    World renamed = build(stackScene(2));
    renamed.grains[3].name = "other";
    const std::string name = refusal(renamed);
    EXPECT_NE(name.find("grain 3 ('other')"), std::string::npos) << name;

    World heavier = build(stackScene(2));
    heavier.grains[5].body.mass *= 1.5;
    EXPECT_NE(refusal(heavier).find("grain 5"), std::string::npos);

    World fewer = build(stackScene(2));
    fewer.grains.pop_back();
    EXPECT_NE(refusal(fewer).find("7 grains"), std::string::npos);
}

// The end a checkpoint kept is the scene's on restart (lsdem-run and Python alike), unless it
// names a boundary the scene lacks: a damaged file, refused (Python indexed past the
// boundaries and crashed; review finding).
TEST(Checkpoint, AKeptEndIsCheckedAgainstTheScenesBoundaries)
{
    Scene scene;
    scene.boundaries.resize(1);
    scene.end.time = 1.0;
    Checkpoint c;
    applyCheckpointEnd(c, scene, "c.lsdem");
    EXPECT_EQ(scene.end.time, 1.0);  // none kept: the scene's own
    EndCondition end;
    end.boundary = 0;
    end.displacement = 0.5;
    c.end = end;
    applyCheckpointEnd(c, scene, "c.lsdem");
    EXPECT_EQ(scene.end.boundary, 0);
    EXPECT_EQ(scene.end.time, 0.0);
    c.end->boundary = 1;
    EXPECT_THROW(applyCheckpointEnd(c, scene, "c.lsdem"), Error);
}
