// ParaView series: the .vtu files are read back by a small independent parser of the VTK XML
// format (VtuReader.h: header, DataArray tags, raw appended block of UInt64 byte counts and
// values) and must hold exactly the posed surfaces, rigid velocities, grain ids and contact
// forces given; the .pvd lists each frame's time and files, drops frames a restart rewrites,
// and a failed write throws an Error and leaves nothing half-written.
#include "lsdem/run/VtkSeries.h"
#include "lsdem/core/Error.h"

#include "support/TestSupport.h"
#include "VtuReader.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <stdexcept>

using namespace lsdem;
using namespace lsdem::test;

namespace {

/// Number of values of @a key per point or cell must match the Piece's counts.
void expectCount(const ParsedGrid& grid, const std::string& key, size_t count)
{
    const ParsedArray& a = grid.at(key);
    EXPECT_EQ(a.reals.size() + a.ints.size(), count * static_cast<size_t>(a.components)) << key;
}

TriangleMesh tetrahedron()
{
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
    return m;
}

/// A 2 x 1 x 0.5 box centred on the origin.
TriangleMesh box()
{
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 0.5 : -0.5, i & 4 ? 0.25 : -0.25});
    m.triangles = {{{0, 2, 3}}, {{0, 3, 1}}, {{4, 5, 7}}, {{4, 7, 6}}, {{0, 1, 5}}, {{0, 5, 4}},
                   {{2, 6, 7}}, {{2, 7, 3}}, {{0, 4, 6}}, {{0, 6, 2}}, {{1, 3, 7}}, {{1, 7, 5}}};
    return m;
}

RigidPose pose(double angle, const Vec3& axis, const Vec3& position)
{
    RigidPose p;
    p.orientation = Quat(Eigen::AngleAxisd(angle, axis.normalized()));
    p.position = position;
    return p;
}

/// Check @a grid holds @a grains in order: posed vertices, rigid velocities, triangles, ids.
void expectGrains(const ParsedGrid& grid, const std::vector<VtkGrain>& grains)
{
    size_t vertexCount = 0, triangleCount = 0;
    for (const VtkGrain& g : grains) {
        vertexCount += g.surface->vertices.size();
        triangleCount += g.surface->triangles.size();
    }
    ASSERT_EQ(grid.points, vertexCount);
    ASSERT_EQ(grid.cells, triangleCount);
    expectCount(grid, "Points/Points", vertexCount);
    expectCount(grid, "PointData/velocity", vertexCount);
    expectCount(grid, "CellData/grain", triangleCount);
    EXPECT_EQ(grid.at("CellData/grain").type, "Int32");
    EXPECT_EQ(grid.at("Points/Points").type, "Float64");
    EXPECT_EQ(grid.at("Cells/connectivity").ints.size(), 3 * triangleCount);
    expectCount(grid, "Cells/offsets", triangleCount);
    expectCount(grid, "Cells/types", triangleCount);

    size_t point = 0, cell = 0;
    for (const VtkGrain& g : grains) {
        const size_t first = point;
        for (const Vec3& local : g.surface->vertices) {
            const Vec3 x = g.pose.toWorld(local);
            EXPECT_EQ(grid.vec3("Points/Points", point), x) << "point " << point;
            const Vec3 expected = g.velocity + g.angularVelocity.cross(x - g.pose.position);
            EXPECT_LT((grid.vec3("PointData/velocity", point) - expected).norm(),
                      1e-14 * (1.0 + expected.norm()))
                << "point " << point;
            ++point;
        }
        for (const auto& t : g.surface->triangles) {
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(grid.at("Cells/connectivity").ints[3 * cell + c],
                          static_cast<std::int64_t>(first) + t[c]);
            EXPECT_EQ(grid.at("Cells/offsets").ints[cell], static_cast<std::int64_t>(3 * (cell + 1)));
            EXPECT_EQ(grid.at("Cells/types").ints[cell], 5);  // VTK_TRIANGLE
            EXPECT_EQ(grid.at("CellData/grain").ints[cell], g.id);
            ++cell;
        }
    }
}

} // namespace

TEST(VtkSeries, GrainFramesHoldPosedSurfacesRigidVelocitiesAndIds)
{
    ScratchDir dir;
    const TriangleMesh tet = tetrahedron(), block = box();
    VtkSeries series(dir.path().string(), "run");

    std::vector<VtkGrain> grains(2);
    grains[0] = {&tet, pose(0.7, {1, 2, 3}, {1.5, -2.0, 0.25}), 3, {0.1, -0.2, 0.3}, {2.0, -1.0, 0.5}};
    grains[1] = {&block, pose(-1.9, {0, 1, -1}, {-4.0, 3.5, 1e-3}), 7, {0, 0, -9.81}, {0, 0, 0}};
    series.writeFrame(0, 0.0, grains, {});
    const ParsedGrid frame0 = parseVtu(dir.file("run_grains_0.vtu"));
    expectGrains(frame0, grains);

    // Next frame: the grains moved and spin differently; the first file is left as it was.
    grains[0].pose = pose(2.2, {-1, 0.3, 0.1}, {1.6, -2.1, 0.2});
    grains[1].pose = pose(0.4, {1, 1, 1}, {-4.0, 3.4, -0.5});
    grains[1].angularVelocity = {0.0, 30.0, -12.5};
    series.writeFrame(1, 0.01, grains, {});
    expectGrains(parseVtu(dir.file("run_grains_1.vtu")), grains);
    EXPECT_EQ(parseVtu(dir.file("run_grains_0.vtu")).arrays.at("Points/Points").reals,
              frame0.arrays.at("Points/Points").reals);
    EXPECT_EQ(series.framesWritten(), 2);
}

// A grain's micromechanics, when every grain of a frame carries them, are point data over its
// surface: displacement, rotation, d2min and the stress's nine entries row by row, each the
// grain's at each of its vertices. A frame whose grains do not all carry them has none.
TEST(VtkSeries, GrainMeasuresArePointDataOverEachGrain)
{
    ScratchDir dir;
    const TriangleMesh tet = tetrahedron(), block = box();
    VtkSeries series(dir.path().string(), "run");
    VtkGrainMeasures first, second;
    first.displacement = {0.1, -0.2, 0.3};
    first.rotation = 0.25;
    first.d2min = 1.5e-4;
    first.stress << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    second.displacement = {-1.0, 0.0, 2.0};
    second.rotation = 3.0;
    second.d2min = 0.0;
    second.stress = -Mat3::Identity();
    std::vector<VtkGrain> grains(2);
    grains[0] = {&tet, pose(0.7, {1, 2, 3}, {1.5, -2.0, 0.25}), 3, {0, 0, 0}, {0, 0, 0}, &first};
    grains[1] = {&block, pose(-1.9, {0, 1, -1}, {-4.0, 3.5, 1e-3}), 7, {0, 0, 0}, {0, 0, 0}, &second};
    series.writeFrame(0, 0.0, grains, {});
    const ParsedGrid grid = parseVtu(dir.file("run_grains_0.vtu"));
    expectGrains(grid, grains);
    size_t point = 0;
    for (const VtkGrain& g : grains)
        for (size_t v = 0; v < g.surface->vertices.size(); ++v, ++point) {
            EXPECT_EQ(grid.vec3("PointData/displacement", point), g.measures->displacement);
            EXPECT_EQ(grid.at("PointData/rotation").reals[point], g.measures->rotation);
            EXPECT_EQ(grid.at("PointData/d2min").reals[point], g.measures->d2min);
            for (int k = 0; k < 9; ++k)
                EXPECT_EQ(grid.at("PointData/stress").reals[9 * point + size_t(k)],
                          g.measures->stress(k / 3, k % 3));
        }
    grains[1].measures = nullptr;
    series.writeFrame(1, 0.01, grains, {});
    const ParsedGrid without = parseVtu(dir.file("run_grains_1.vtu"));
    EXPECT_EQ(without.arrays.count("PointData/d2min"), 0u);
    expectGrains(without, grains);
}

TEST(VtkSeries, ContactFramesHoldOneVertexPerForcePoint)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    const std::vector<VtkForcePoint> forces = {{{0.5, 1.0, -2.0}, {1e3, -2.5, 0.125}, 0},
                                               {{3.0, -1.0, 1.0 / 3.0}, {0.0, 0.0, -7.0}, 12},
                                               {{-1.0, 0.0, 0.0}, {-4.0, 5.0, 6.0}, -2}};
    series.writeFrame(0, 0.5, {}, forces);
    const ParsedGrid grid = parseVtu(dir.file("frames_contacts_0.vtu"));
    ASSERT_EQ(grid.points, 3u);
    ASSERT_EQ(grid.cells, 3u);
    expectCount(grid, "Points/Points", 3);
    expectCount(grid, "PointData/force", 3);
    expectCount(grid, "PointData/grain", 3);
    EXPECT_EQ(grid.at("PointData/grain").type, "Int32");
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(grid.vec3("Points/Points", i), forces[i].point);
        EXPECT_EQ(grid.vec3("PointData/force", i), forces[i].force);
        EXPECT_EQ(grid.at("PointData/grain").ints.at(i), forces[i].grain);
        EXPECT_EQ(grid.at("Cells/connectivity").ints.at(i), static_cast<std::int64_t>(i));
        EXPECT_EQ(grid.at("Cells/offsets").ints.at(i), static_cast<std::int64_t>(i + 1));
        EXPECT_EQ(grid.at("Cells/types").ints.at(i), 1);  // VTK_VERTEX
    }
}

TEST(VtkSeries, EmptyFramesAreStillCompleteFiles)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, 0.0, {}, {});
    for (const char* name : {"frames_grains_0.vtu", "frames_contacts_0.vtu"}) {
        const ParsedGrid grid = parseVtu(dir.file(name));
        EXPECT_EQ(grid.points, 0u) << name;
        EXPECT_EQ(grid.cells, 0u) << name;
        // Every array is still declared (ParaView looks for them), with a zero byte count.
        for (const char* key : {"Points/Points", "Cells/connectivity", "Cells/offsets", "Cells/types"})
            expectCount(grid, key, 0);
    }
    expectCount(parseVtu(dir.file("frames_contacts_0.vtu")), "PointData/force", 0);
    expectCount(parseVtu(dir.file("frames_grains_0.vtu")), "PointData/velocity", 0);
}

TEST(VtkSeries, CollectionListsEachFrameWithItsTimeAndFiles)
{
    ScratchDir dir;
    const TriangleMesh tet = tetrahedron();
    VtkSeries series(dir.path().string(), "frames");
    const std::vector<VtkGrain> grains = {{&tet, RigidPose(), 0, Vec3::Zero(), Vec3::Zero()}};
    const double times[] = {0.0, 0.1, 1.0 / 3.0};  // 0.1 and 1/3 need all 17 digits
    for (int k = 0; k < 3; ++k) series.writeFrame(k, times[k], grains, {});

    const std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 6u);
    for (size_t k = 0; k < 3; ++k) {
        for (int part = 0; part < 2; ++part) {
            const DataSetEntry& e = entries[2 * k + static_cast<size_t>(part)];
            EXPECT_EQ(e.time, times[k]);
            EXPECT_EQ(e.part, part);
            EXPECT_EQ(e.file, std::string(part == 0 ? "frames_grains_" : "frames_contacts_") +
                                  std::to_string(k) + ".vtu");
            EXPECT_TRUE(std::filesystem::exists(dir.path() / e.file)) << e.file;
        }
    }
    EXPECT_EQ(series.frameTimes(), std::vector<double>(std::begin(times), std::end(times)));
}

TEST(VtkSeries, RewritingAFrameDropsTheLaterOnes)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, 0.0, {}, {});
    series.writeFrame(1, 1.0, {}, {});
    series.writeFrame(2, 2.0, {}, {});
    series.writeFrame(1, 1.5, {}, {});  // a restart from between frames 0 and 1

    EXPECT_EQ(series.framesWritten(), 2);
    EXPECT_EQ(series.frameTimes(), (std::vector<double>{0.0, 1.5}));
    const std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 4u);
    EXPECT_EQ(entries[2].time, 1.5);
    EXPECT_EQ(entries[3].file, "frames_contacts_1.vtu");
    EXPECT_EQ(readFile(dir.file("frames.pvd")).find("_2.vtu"), std::string::npos);
}

TEST(VtkSeries, RestoredTimesAreListedBeforeTheNextFrame)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    series.restoreFrameTimes({0.0, 0.25});
    EXPECT_THROW(series.writeFrame(3, 1.0, {}, {}), std::invalid_argument);  // would leave a hole
    EXPECT_THROW(series.writeFrame(-1, 1.0, {}, {}), std::invalid_argument);
    series.writeFrame(2, 0.5, {}, {});
    const std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 6u);
    EXPECT_EQ(entries[0].time, 0.0);
    EXPECT_EQ(entries[2].time, 0.25);
    EXPECT_EQ(entries[4].time, 0.5);
    EXPECT_EQ(entries[4].file, "frames_grains_2.vtu");
}

TEST(VtkSeries, MissingFolderThrowsAndWritesNothing)
{
    ScratchDir dir;
    VtkSeries series(dir.file("no-such-folder"), "frames");
    try {
        series.writeFrame(0, 0.0, {}, {});
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(e.where().find("frames_grains_0.vtu"), std::string::npos) << e.what();
        EXPECT_FALSE(e.fix().empty()) << e.what();
    }
    EXPECT_EQ(dir.entryCount(), 0u);
    EXPECT_EQ(series.framesWritten(), 0);
}

TEST(VtkSeries, FailedCollectionLeavesTheSeriesAsItWas)
{
    ScratchDir dir;
    VtkSeries series(dir.path().string(), "frames");
    series.writeFrame(0, 0.0, {}, {});
    const std::string before = readFile(dir.file("frames.pvd"));

    // Something in the way of the .pvd: the frame's files are complete, the list unchanged.
    std::filesystem::remove(dir.file("frames.pvd"));
    std::filesystem::create_directory(dir.file("frames.pvd"));
    try {
        series.writeFrame(1, 1.0, {}, {});
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(e.where().find("frames.pvd"), std::string::npos) << e.what();
    }
    EXPECT_EQ(series.framesWritten(), 1);
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
            << entry.path();

    // Cleared, the same frame goes through and the list is as if nothing had failed.
    std::filesystem::remove(dir.file("frames.pvd"));
    series.writeFrame(1, 1.0, {}, {});
    EXPECT_EQ(parsePvd(dir.file("frames.pvd")).size(), 4u);
    EXPECT_NE(readFile(dir.file("frames.pvd")), before);
}

// A parallel frame (one simulation over ranks): two "ranks" each write their piece, rank 0 the
// .pvtu files. Each .pvtu names the pieces and declares exactly the arrays every piece holds
// (name, type, components: what a VTK reader matches them by); the pieces hold each rank's
// grains; the .pvd names the .pvtu files; a series restored in that folder (a restart) lists
// the frame as parallel again, and a later single-process frame as a plain one.
TEST(VtkSeries, ParallelFramesNameTheirPiecesAndDeclareTheirArrays)
{
    ScratchDir dir;
    const TriangleMesh tet = tetrahedron(), cube = box();
    RigidPose moved;
    moved.position = Vec3(3, 0, 0);
    VtkSeries rank0(dir.path().string(), "frames"), rank1(dir.path().string(), "frames");
    rank1.writeParallelFrame(0, 0.5, 1, 2, {{&cube, moved, 7, Vec3::Zero(), Vec3::Zero()}},
                             {{Vec3(1, 2, 3), Vec3(0, 0, -1), 7}});
    rank0.writeParallelFrame(0, 0.5, 0, 2, {{&tet, RigidPose(), 2, Vec3::Zero(), Vec3::Zero()}},
                             {});
    EXPECT_EQ(rank1.framesWritten(), 1);
    EXPECT_FALSE(std::filesystem::exists(dir.file("frames_grains_0.vtu")));

    const std::vector<DataSetEntry> entries = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(entries.size(), 2u);
    EXPECT_EQ(entries[0].file, "frames_grains_0.pvtu");
    EXPECT_EQ(entries[1].file, "frames_contacts_0.pvtu");
    EXPECT_EQ(entries[0].time, 0.5);

    static const std::regex pieceTag(R"__(<Piece Source="([^"]*)"/>)__");
    static const std::regex arrayTag(R"__(<PDataArray ([^>]*)/>)__");
    for (const char* kind : {"grains", "contacts"}) {
        const std::string text = readFile(dir.file(std::string("frames_") + kind + "_0.pvtu"));
        EXPECT_NE(text.find("<VTKFile type=\"PUnstructuredGrid\""), std::string::npos);
        std::vector<std::string> pieces;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), pieceTag);
             it != std::sregex_iterator(); ++it)
            pieces.push_back((*it)[1]);
        ASSERT_EQ(pieces.size(), 2u) << kind;
        std::map<std::string, std::pair<std::string, int>> declared;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), arrayTag);
             it != std::sregex_iterator(); ++it) {
            const auto a = attributesOf((*it)[1]);
            declared[a.at("Name")] = {a.at("type"), std::stoi(a.at("NumberOfComponents"))};
        }
        for (int p = 0; p < 2; ++p) {
            EXPECT_EQ(pieces[size_t(p)], std::string("frames_") + kind + "_0_" +
                                             std::to_string(p) + ".vtu");
            const ParsedGrid grid = parseVtu(dir.file(pieces[size_t(p)]));
            // Every data array of the piece (not its cells' structure) is declared alike.
            size_t dataArrays = 0;
            for (const auto& [key, array] : grid.arrays) {
                if (key.rfind("Cells/", 0) == 0) continue;
                const std::string name = key.substr(key.find('/') + 1);
                ++dataArrays;
                ASSERT_TRUE(declared.count(name)) << kind << ": " << name;
                EXPECT_EQ(declared.at(name).first, array.type) << name;
                EXPECT_EQ(declared.at(name).second, array.components) << name;
            }
            EXPECT_EQ(dataArrays, declared.size()) << kind;
        }
    }
    // Each piece holds its rank's grain: the tetrahedron (4 points) and the box (8).
    const ParsedGrid first = parseVtu(dir.file("frames_grains_0_0.vtu"));
    const ParsedGrid second = parseVtu(dir.file("frames_grains_0_1.vtu"));
    EXPECT_EQ(first.points, 4u);
    EXPECT_EQ(second.points, 8u);
    EXPECT_EQ(first.at("CellData/grain").ints, std::vector<std::int64_t>(4, 2));
    EXPECT_EQ(second.at("CellData/grain").ints, std::vector<std::int64_t>(12, 7));
    EXPECT_EQ(second.vec3("Points/Points", 0), Vec3(2, -0.5, -0.25));
    EXPECT_EQ(parseVtu(dir.file("frames_contacts_0_1.vtu")).points, 1u);
    EXPECT_EQ(parseVtu(dir.file("frames_contacts_0_0.vtu")).points, 0u);

    VtkSeries restarted(dir.path().string(), "frames");
    restarted.restoreFrameTimes({0.5});
    restarted.writeFrame(1, 0.75, {}, {});
    const std::vector<DataSetEntry> after = parsePvd(dir.file("frames.pvd"));
    ASSERT_EQ(after.size(), 4u);
    EXPECT_EQ(after[0].file, "frames_grains_0.pvtu");
    EXPECT_EQ(after[2].file, "frames_grains_1.vtu");
    EXPECT_THROW(rank0.writeParallelFrame(0, 0.5, 2, 2, {}, {}), std::invalid_argument);
}
