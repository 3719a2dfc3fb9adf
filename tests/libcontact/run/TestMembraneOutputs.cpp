// A run's outputs of a world with membranes: each ParaView frame also holds the membranes as
// one grid of triangles (frames_membranes_<k>.vtu, part 2 of the frame in the .pvd), read back
// by VtuReader.h and compared exactly with the membranes' vertices, velocities, the grains'
// push, the held vertices and the triangles; each membrane's history (membrane_<name>.csv)
// reads back its pressure, enclosed volume, energies and the grains' push. A world without
// membranes writes no such file and the .pvd it always wrote. A whole run of a scene with a
// membrane writes both, and its checkpoint holds the membrane: a run stopped and continued
// writes what a run straight through writes.
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/RunOutputs.h"
#include "lsdem/run/SimulationRun.h"
#include "lsdem/run/VtkSeries.h"

#include "lsdem/core/CsvText.h"
#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include "support/TestSupport.h"
#include "support/TestAssets.h"
#include "VtuReader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace lsdem;
using namespace lsdem::test;

namespace {

/// A ball of six nodes (radius 1) in a latex tube of radius 0.99 (12 segments, so four of its
/// vertices face the ball's sideways nodes, which press 0.01 into it), under pressure 0.05,
/// its bottom ring held by the floor (boundary 0); and a second, smaller tube away from it,
/// free and touched by nothing. Units: mm, N, s, tonne.
World ballInTubes()
{
    World w;
    w.materialCount = 1;
    ContactModel law;
    law.formulation = Formulation::Original;
    law.normalStiffness = 10.0;
    w.models = {law};
    Grain ball;
    ball.name = "ball";
    ball.asset = std::make_shared<const GrainAsset>(lsdem::test::sixNodeAsset(2.0));
    ball.body.mass = 3.3e-8;
    ball.body.principalInertia = Vec3::Constant(1.3e-8);
    w.grains.push_back(ball);
    Boundary floor;
    floor.name = "floor";
    floor.plane.point = Vec3(0, 0, -2);
    w.boundaries.push_back(floor);

    Membrane tube = makeTubeMembrane(Vec3(0, 0, -2), Vec3::UnitZ(), 0.99, 4.0, 12, 4, lsdem::test::latexRubber());
    tube.name = "tube";
    tube.pressure = 0.05;
    for (size_t v = 0; v < 12; ++v) tube.heldBy[v] = 0;
    w.membranes.push_back(tube);
    Membrane other = makeTubeMembrane(Vec3(10, 0, -2), Vec3::UnitZ(), 0.5, 1.0, 6, 2, lsdem::test::latexRubber());
    other.name = "other tube";
    w.membranes.push_back(other);
    return w;
}

/// A short run of ballInTubes: the grains' push on the tube is filled, the tube has moved.
Simulation runBallInTubes(int steps)
{
    const World w = ballInTubes();
    // A tenth of the rubber's stable step; the contact's is far longer (ω·dt ≈ 0.01).
    Simulation sim(w, 0.1 * membraneStableStep(w.membranes[0]));
    for (int s = 0; s < steps; ++s) sim.step();
    return sim;
}

double number(const std::string& text)
{
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    EXPECT_EQ(*end, '\0') << "not a number: '" << text << "'";
    return v;
}

/// The lines of the CSV file at @a path, each split into its fields.
std::vector<std::vector<std::string>> csvLines(const std::string& path)
{
    return readCsvRecords(readFile(path), path);
}

std::set<std::string> filesIn(const ScratchDir& dir)
{
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        names.insert(entry.path().filename().string());
    return names;
}

} // namespace

// A frame of a world with two membranes: one .vtu of both, listed as the frame's part 2, whose
// points are the membranes' vertices in order (the first's, then the second's), each with its
// velocity, the grains' push and whether it is held, and whose triangles are theirs (the
// second's numbered on from the first's vertices), each with its membrane's index.
TEST(MembraneOutputs, FramesHoldEveryMembranesTrianglesAndVertexData)
{
    ScratchDir dir;
    const Simulation sim = runBallInTubes(20);
    const std::vector<Membrane>& membranes = sim.world().membranes;
    const Membrane& tube = membranes[0];
    double pushed = 0.0;
    for (const Vec3& f : tube.grainForces) pushed += f.norm();
    ASSERT_GT(pushed, 0.0) << "the ball must press on the tube for the push to be checked";

    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, sim.world().time, {}, {}, membranes);
    const std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 3u);
    EXPECT_EQ(entries[2].part, 2);
    EXPECT_EQ(entries[2].file, "frames_membranes_0.vtu");
    EXPECT_EQ(entries[2].time, sim.world().time);

    const ParsedGrid grid = parseVtu(dir.file(entries[2].file));
    ASSERT_EQ(grid.points, tube.positions.size() + membranes[1].positions.size());
    ASSERT_EQ(grid.cells, tube.triangles.size() + membranes[1].triangles.size());
    EXPECT_EQ(grid.at("PointData/held").type, "Int32");
    EXPECT_EQ(grid.at("CellData/membrane").type, "Int32");
    ASSERT_EQ(grid.at("Points/Points").reals.size(), 3 * grid.points);
    ASSERT_EQ(grid.at("PointData/velocity").reals.size(), 3 * grid.points);
    ASSERT_EQ(grid.at("PointData/grain_force").reals.size(), 3 * grid.points);
    ASSERT_EQ(grid.at("PointData/held").ints.size(), grid.points);
    ASSERT_EQ(grid.at("Cells/connectivity").ints.size(), 3 * grid.cells);
    ASSERT_EQ(grid.at("Cells/offsets").ints.size(), grid.cells);
    ASSERT_EQ(grid.at("Cells/types").ints.size(), grid.cells);
    ASSERT_EQ(grid.at("CellData/membrane").ints.size(), grid.cells);

    size_t point = 0, cell = 0;
    for (size_t k = 0; k < membranes.size(); ++k) {
        const Membrane& m = membranes[k];
        const size_t first = point;
        for (size_t v = 0; v < m.positions.size(); ++v, ++point) {
            EXPECT_EQ(grid.vec3("Points/Points", point), m.positions[v]) << "point " << point;
            EXPECT_EQ(grid.vec3("PointData/velocity", point), m.velocities[v]);
            EXPECT_EQ(grid.vec3("PointData/grain_force", point), m.grainForces[v]);
            EXPECT_EQ(grid.at("PointData/held").ints[point], m.heldBy[v] >= 0 ? 1 : 0);
        }
        for (const MembraneTriangle& t : m.triangles) {
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(grid.at("Cells/connectivity").ints[3 * cell + size_t(c)],
                          static_cast<std::int64_t>(first) + t.vertices[size_t(c)]);
            EXPECT_EQ(grid.at("Cells/offsets").ints[cell], std::int64_t(3 * (cell + 1)));
            EXPECT_EQ(grid.at("Cells/types").ints[cell], 5);  // VTK_TRIANGLE
            EXPECT_EQ(grid.at("CellData/membrane").ints[cell], std::int64_t(k));
            ++cell;
        }
    }
    // The held ring is the tube's first 12 vertices; the others are free.
    EXPECT_EQ(grid.at("PointData/held").ints[11], 1);
    EXPECT_EQ(grid.at("PointData/held").ints[12], 0);
}

// The membranes part follows each frame: a frame written without membranes lists none (and a
// restart that rewrites a frame drops what the frame had), and a series restored in the folder
// lists a frame's membranes again where their file is.
TEST(MembraneOutputs, EachFrameListsItsOwnMembranesPart)
{
    ScratchDir dir;
    const World w = ballInTubes();
    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, 0.0, {}, {}, w.membranes);
    series.writeFrame(1, 1.0, {}, {});
    series.writeFrame(2, 2.0, {}, {}, w.membranes);
    std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 8u);  // 3 + 2 + 3
    EXPECT_EQ(entries[2].file, "frames_membranes_0.vtu");
    EXPECT_EQ(entries[4].file, "frames_contacts_1.vtu");
    EXPECT_EQ(entries[7].file, "frames_membranes_2.vtu");
    EXPECT_EQ(entries[7].time, 2.0);
    EXPECT_FALSE(std::filesystem::exists(dir.file("frames_membranes_1.vtu")));

    VtkSeries restarted(dir.path().string(), "frames");
    restarted.restoreFrameTimes({0.0, 1.0});
    restarted.writeFrame(2, 1.5, {}, {});
    entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 7u);  // 3 + 2 + 2
    EXPECT_EQ(entries[2].file, "frames_membranes_0.vtu");
    EXPECT_EQ(entries[6].file, "frames_contacts_2.vtu");
}

// Each membrane's history row: step, time, pressure, enclosed volume, strain and kinetic
// energy, the grains' push summed (x, y, z) and its magnitudes summed; written to
// membrane_<name>.csv (the name made safe as boundaries' are) and read back exactly.
TEST(MembraneOutputs, HistoryRowsReadBackAsTheMembranesStateThen)
{
    ScratchDir dir;
    const World w = ballInTubes();
    Simulation sim(w, 0.1 * membraneStableStep(w.membranes[0]));
    RunRecord record;
    for (int row = 0; row < 3; ++row) {
        if (row > 0)
            for (int s = 0; s < 10; ++s) sim.step();
        recordHistoryRow(sim, record);
    }
    ASSERT_EQ(record.membraneRows.size(), 2u);
    writeHistoryFiles(dir.path().string(), sim.world(), record);
    EXPECT_EQ(filesIn(dir), (std::set<std::string>{"energy.csv", "boundary_floor.csv",
                                                    "membrane_tube.csv",
                                                    "membrane_other_tube.csv"}));
    EXPECT_EQ(membraneHistoryFileName("other tube"), "membrane_other_tube.csv");
    EXPECT_TRUE(isMembraneHistoryFileName("membrane_tube.csv"));
    EXPECT_FALSE(isMembraneHistoryFileName("boundary_tube.csv"));

    for (size_t k = 0; k < 2; ++k) {
        const Membrane& m = sim.world().membranes[k];
        const std::string path = dir.file(membraneHistoryFileName(m.name));
        EXPECT_TRUE(isRunTextOutput(path));
        const auto lines = csvLines(path);
        ASSERT_EQ(lines.size(), 4u) << path;  // the header and a row per history row
        std::string header;
        for (const std::string& f : lines[0]) header += (header.empty() ? "" : ",") + f;
        EXPECT_EQ(header, "step,time,pressure,volume,strain_energy,kinetic,grain_fx,grain_fy,"
                          "grain_fz,grain_force_magnitude_sum");
        for (size_t r = 0; r < 3; ++r) {
            ASSERT_EQ(lines[r + 1].size(), 10u);
            EXPECT_EQ(number(lines[r + 1][0]), 10.0 * double(r));
            for (size_t c = 0; c < 10; ++c)
                EXPECT_EQ(number(lines[r + 1][c]), record.membraneRows[k][r][c]) << r << "," << c;
        }
        // The last row is the membrane now.
        const std::vector<std::string>& last = lines[3];
        Vec3 push = Vec3::Zero();
        double magnitudes = 0.0;
        for (const Vec3& f : m.grainForces) {
            push += f;
            magnitudes += f.norm();
        }
        EXPECT_EQ(number(last[1]), sim.world().time);
        EXPECT_EQ(number(last[2]), m.pressure);
        EXPECT_EQ(number(last[3]), enclosedVolume(m));
        EXPECT_EQ(number(last[4]), m.strainEnergy);
        EXPECT_EQ(number(last[5]), membraneKineticEnergy(m));
        EXPECT_EQ(Vec3(number(last[6]), number(last[7]), number(last[8])), push);
        EXPECT_EQ(number(last[9]), magnitudes);
        if (k == 0) {
            EXPECT_GT(magnitudes, 0.0);  // the ball presses on the tube ...
        } else {
            EXPECT_EQ(magnitudes, 0.0);  // ... and on nothing else
        }
    }
}

// Without membranes: no membranes file, no membrane history, and the .pvd lists two parts a
// frame, byte for byte as it did before membranes were written.
TEST(MembraneOutputs, AWorldWithoutMembranesWritesWhatItAlwaysWrote)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, 0.0, {}, {});
    series.writeFrame(1, 0.1, {}, {}, {});
    EXPECT_EQ(filesIn(dir), (std::set<std::string>{"frames.pvd", "frames_grains_0.vtu",
                                                    "frames_contacts_0.vtu", "frames_grains_1.vtu",
                                                    "frames_contacts_1.vtu"}));
    EXPECT_EQ(readFile(dir.file("frames.pvd")),
              "<?xml version=\"1.0\"?>\n"
              "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" "
              "header_type=\"UInt64\">\n"
              "  <Collection>\n"
              "    <DataSet timestep=\"0\" part=\"0\" file=\"frames_grains_0.vtu\"/>\n"
              "    <DataSet timestep=\"0\" part=\"1\" file=\"frames_contacts_0.vtu\"/>\n"
              "    <DataSet timestep=\"0.10000000000000001\" part=\"0\" "
              "file=\"frames_grains_1.vtu\"/>\n"
              "    <DataSet timestep=\"0.10000000000000001\" part=\"1\" "
              "file=\"frames_contacts_1.vtu\"/>\n"
              "  </Collection>\n"
              "</VTKFile>\n");

    ScratchDir history;
    World w = ballInTubes();
    w.membranes.clear();
    Simulation sim(std::move(w), 1e-6);
    RunRecord record;
    recordHistoryRow(sim, record);
    writeHistoryFiles(history.path().string(), sim.world(), record);
    EXPECT_TRUE(record.membraneRows.empty());
    EXPECT_EQ(filesIn(history), (std::set<std::string>{"energy.csv", "boundary_floor.csv"}));
}

// A scene with a membrane, run as lsdem-run runs it: every frame lists its membranes part,
// the membrane's history has a row per history step, and a run stopped half-way and continued
// from its checkpoint ends with the same bytes in every history file as a run straight through
// (the membrane's state and rows are in the checkpoint).
TEST(MembraneOutputs, ASceneWithAMembraneRunsAndRestartsAsOneRun)
{
    ScratchDir dir;
    const std::string scene = dir.file("scene.toml");
    std::ofstream(scene) << R"([assets.ball]
shape = "sphere"
radius = 1.0
voxel = 0.25
nodes = 100

[materials.steel]
density = 7.85e-9
[materials.wall]
density = 0.0
[materials.latex]
density = 0.0

[[contacts]]
materials = ["steel", "wall"]
normal_stiffness = 1e3
[[contacts]]
materials = ["steel", "latex"]
normal_stiffness = 1e3

[[grains]]
asset = "ball"
material = "steel"
position = [0, 0, 3]

[[boundaries]]
name = "floor"
type = "plane"
material = "wall"
point = [0, 0, 0]
normal = [0, 0, 1]

[[membranes]]
name = "sleeve"
material = "latex"
shape = "tube"
youngs = 1.4
poisson = 0.45
thickness = 0.3
density = 1e-6
pressure = 0.1
base = [0, 0, 0]
axis = [0, 0, 1]
radius = 1.5
height = 6
segments = 12
rings = 4
hold = ["floor"]

[simulation]
time_step = 1e-6
end_steps = 100

[output]
history_every = 25
vtk_period = 5e-5
)";
    RunOptions options;
    options.scenePath = scene;
    options.outDir = dir.file("out");
    std::ostringstream log;
    const RunResult result = runSimulation(options, log);
    EXPECT_FALSE(result.interrupted);
    EXPECT_EQ(result.step, 100);
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/checkpoint.lsdem")));

    RunOptions stopped = options;
    stopped.outDir = dir.file("halves");
    stopped.stopAtStep = 60;
    const RunResult first = runSimulation(stopped, log);
    ASSERT_TRUE(first.interrupted);
    EXPECT_EQ(first.step, 60);
    RunOptions resumed;
    resumed.restartPath = first.checkpointPath;
    const RunResult second = runSimulation(resumed, log);
    EXPECT_FALSE(second.interrupted);
    EXPECT_EQ(second.step, 100);
    for (const char* file : {"membrane_sleeve.csv", "energy.csv", "boundary_floor.csv", "grains.csv"})
        EXPECT_EQ(readFile(dir.file(std::string("halves/") + file)),
                  readFile(dir.file(std::string("out/") + file)))
            << file;
    // A world the scene no longer makes is refused: one without the membrane, or with another
    // number of vertices.
    std::vector<std::string> warnings;
    const Scene read = readSceneFile(scene);
    for (int change = 0; change < 2; ++change) {
        Scene other = read;
        if (change == 0) other.membranes.clear();
        else other.membranes[0].segments += 1;
        World w = buildWorld(other, warnings);
        try {
            restoreWorldState(first.checkpointPath, w);
            ADD_FAILURE() << "restored into a changed scene";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(change == 0 ? "holds 1 membranes and its scene makes 0"
                                                              : "membrane 'sleeve' has another number of vertices"),
                      std::string::npos)
                << e.what();
        }
    }

    EXPECT_EQ(csvLines(dir.file("out/membrane_sleeve.csv")).size(), 1u + 5u);  // steps 0 ... 100
    const std::vector<DataSetEntry> entries = parsePvd(dir.file("out/frames.pvd"));
    ASSERT_EQ(entries.size(), 3u * 3u);  // steps 0, 50, 100
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(entries[3 * k + 2].part, 2);
        EXPECT_EQ(entries[3 * k + 2].file, "frames_membranes_" + std::to_string(k) + ".vtu");
        const ParsedGrid grid = parseVtu(dir.file("out/" + entries[3 * k + 2].file));
        EXPECT_EQ(grid.points, 12u * 5u);
        EXPECT_EQ(grid.cells, 2u * 12u * 4u);
    }
}
