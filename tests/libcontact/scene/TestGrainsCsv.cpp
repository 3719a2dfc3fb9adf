// Grains from a CSV table ([[grain_files]]): a table reads to the grains it lists and writes
// back to the same numbers, a scene with a grain file writes back as a reference to it, bad
// tables are refused naming the file, line and column, and overlapping grains (measured with
// the level sets) are refused naming both grains and the depth.
#include "lsdem/scene/GrainsCsv.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace lsdem;
using namespace lsdem::test;

namespace {

/// The 1-based line of the first occurrence of @a text in @a scene.
int lineOf(const std::string& scene, const std::string& text)
{
    const size_t at = scene.find(text);
    return 1 + static_cast<int>(std::count(scene.begin(), scene.begin() + static_cast<long>(at), '\n'));
}

/// A scene with two assets (analytic spheres of radius 2 and 1.5, baked at load), two
/// materials, and a grain file "packing.csv" beside it.
std::string sceneText(const std::string& extra = "")
{
    return R"([assets.big]
shape = "sphere"
radius = 2.0
voxel = 0.25
nodes = 300

[assets.small]
shape = "sphere"
radius = 1.5
voxel = 0.25
nodes = 200

[materials.sand]
density = 2.65e-9
[materials.glass]
density = 2.5e-9

[[contacts]]
materials = ["sand", "sand"]
normal_stiffness = 1e3
[[contacts]]
materials = ["sand", "glass"]
normal_stiffness = 1e3
[[contacts]]
materials = ["glass", "glass"]
normal_stiffness = 1e3

[[grains]]
name = "first"
asset = "big"
material = "glass"
position = [0, 0, -10]

[[grain_files]]
file = "packing.csv"
material = "sand"
)" + extra + R"(
[simulation]
time_step = 1e-6
end_steps = 10
)";
}

const std::string kPacking = "name,asset,x,y,z,qw,qx,qy,qz,vx,vy,vz\n"
                             "a,big,0,0,0,1,0,0,0,0,0,0\n"
                             "\"b, the second\",small,4.0,0.1,-0.2,0.5,0.5,0.5,0.5,1e-3,0,-2\n"
                             "c,small,0,4.5,0.25,0.70710678,0,0.70710678,0,0,0,0\n";

struct Folder
{
    ScratchDir dir;
    std::string scene;
    Folder(const std::string& packing, const std::string& extra = "")
    {
        scene = dir.file("scene.toml");
        std::ofstream(scene) << sceneText(extra);
        std::ofstream(dir.file("packing.csv")) << packing;
    }
};

} // namespace

TEST(GrainsCsv, TableReadsToTheGrainsItLists)
{
    const Folder f(kPacking);
    const Scene s = readSceneFile(f.scene);
    ASSERT_EQ(s.grains.size(), 4u);
    ASSERT_EQ(s.grainFiles.size(), 1u);
    EXPECT_EQ(s.grainFiles[0].first, 1u);
    EXPECT_EQ(s.grainFiles[0].count, 3u);
    EXPECT_EQ(s.grainFiles[0].file, f.dir.file("packing.csv"));
    const GrainSpec& b = s.grains[2];
    EXPECT_EQ(b.name, "b, the second");
    EXPECT_EQ(s.assets[size_t(b.asset)].name, "small");
    EXPECT_EQ(s.materials[size_t(b.material)].name, "sand");
    EXPECT_EQ(b.pose.position, Vec3(4.0, 0.1, -0.2));
    EXPECT_EQ(b.pose.orientation.coeffs(), Quat(0.5, 0.5, 0.5, 0.5).coeffs());
    EXPECT_EQ(b.velocity, Vec3(1e-3, 0, -2));
    EXPECT_EQ(b.where, f.dir.file("packing.csv") + ":3");
    // An 8-digit quaternion is normalised.
    EXPECT_NEAR(s.grains[3].pose.orientation.norm(), 1.0, 1e-15);
    EXPECT_NEAR(s.grains[3].pose.orientation.y(), std::sqrt(0.5), 1e-15);
}

// The table a scene's grains write to reads back to the same numbers, bit for bit; a scene with
// a grain file writes a reference to it and reads back to the same grains.
TEST(GrainsCsv, WritesAndReadsBackTheSameGrains)
{
    const Folder f(kPacking);
    const Scene s = readSceneFile(f.scene);
    const std::string text = grainsCsvText(s, 1, 3);
    Scene again = s;
    again.grains.resize(1);
    readGrainsCsv(text, "again.csv", 0, again);
    ASSERT_EQ(again.grains.size(), s.grains.size());
    for (size_t i = 1; i < s.grains.size(); ++i) {
        EXPECT_EQ(again.grains[i].name, s.grains[i].name);
        EXPECT_EQ(again.grains[i].asset, s.grains[i].asset);
        EXPECT_EQ(again.grains[i].material, s.grains[i].material);
        EXPECT_EQ(again.grains[i].pose.position, s.grains[i].pose.position);
        EXPECT_EQ(again.grains[i].pose.orientation.coeffs(), s.grains[i].pose.orientation.coeffs());
        EXPECT_EQ(again.grains[i].velocity, s.grains[i].velocity);
    }
    // The scene writer refers to the file (relative to the scene) instead of listing its grains.
    const std::string toml = sceneToToml(s, f.dir.path().string());
    EXPECT_NE(toml.find("[[grain_files]]\nfile = 'packing.csv'\nmaterial = 'sand'"),
              std::string::npos) << toml;
    EXPECT_EQ(toml.find("b, the second"), std::string::npos) << toml;
    const std::string written = f.dir.file("written.toml");
    writeSceneFile(s, written);
    const Scene back = readSceneFile(written);
    ASSERT_EQ(back.grains.size(), s.grains.size());
    for (size_t i = 0; i < s.grains.size(); ++i) {
        EXPECT_EQ(back.grains[i].name, s.grains[i].name);
        EXPECT_EQ(back.grains[i].pose.position, s.grains[i].pose.position);
        EXPECT_EQ(back.grains[i].pose.orientation.coeffs(), s.grains[i].pose.orientation.coeffs());
        EXPECT_EQ(back.grains[i].material, s.grains[i].material);
    }
    // A material per grain becomes a column.
    Scene mixed = s;
    mixed.grains[2].material = 1;
    EXPECT_EQ(grainsCsvText(mixed, 1, 3).rfind("name,material,asset,", 0), 0u);
}

// A quaternion off unit length (text written with few digits) is normalised once; written
// back exactly and read again it is the same, bit for bit: a normalised quaternion is not
// normalised again (that can move its last bit; found by fuzz/FuzzGrainsCsv.cpp).
TEST(GrainsCsv, ANormalisedQuaternionReadsBackBitForBit)
{
    Scene s;
    s.assets.push_back(AssetSpec{});
    s.assets.back().name = "ball";
    s.materials.push_back({"glass", 1e-9});
    const std::string text = "asset,x,y,z,qw,qx,qy,qz\n"
                             "ball,4,5,6,0.99994,0,0,0.0044721\n"
                             "ball,0,0,0,0.5,0.5,0.5,0.50001\n";
    readGrainsCsv(text, "off.csv", 0, s);
    ASSERT_EQ(s.grains.size(), 2u);
    for (int round = 0; round < 3; ++round) {
        Scene again = s;
        again.grains.clear();
        readGrainsCsv(grainsCsvText(s, 0, s.grains.size()), "again.csv", 0, again);
        ASSERT_EQ(again.grains.size(), 2u);
        for (size_t i = 0; i < 2; ++i)
            EXPECT_EQ(again.grains[i].pose.orientation.coeffs(), s.grains[i].pose.orientation.coeffs())
                << "grain " << i << ", round " << round;
        s = again;
    }
    // And it is a rotation: unit to rounding.
    for (const GrainSpec& g : s.grains)
        EXPECT_NEAR(g.pose.orientation.squaredNorm(), 1.0, 1e-15);
}

TEST(GrainsCsv, BadTablesAreRefusedWithFileLineAndColumn)
{
    struct Case
    {
        const char* what;
        std::string packing;
        int line;             ///< 0: the file key of the scene's [[grain_files]]
        const char* message;
    };
    const std::string header = "asset,x,y,z,qw,qx,qy,qz\n";
    const Case cases[] = {
        {"missing column", "asset,x,y,qw,qx,qy,qz\nbig,0,0,1,0,0,0\n", 1, "missing column 'z'"},
        {"unknown column", "asset,x,y,z,qw,qx,qy,qz,colour\nbig,0,0,0,1,0,0,0,red\n", 1, "unknown column 'colour'"},
        {"unknown asset", header + "big,0,0,0,1,0,0,0\nhuge,5,0,0,1,0,0,0\n", 3, "no asset named 'huge'"},
        {"NaN", header + "big,0,0,nan,1,0,0,0\n", 2, "column 'z': is not finite"},
        {"not a number", header + "big,0,0,0,1,0,0,zero\n", 2, "column 'qz': 'zero' is not a number"},
        {"short row", header + "big,0,0,0,1,0,0\n", 2, "has 7 fields, the header 8"},
        {"zero quaternion", header + "big,0,0,0,0,0,0,0\n", 2, "is not a rotation (zero quaternion)"},
        {"unknown material", "asset,material,x,y,z,qw,qx,qy,qz\nbig,steel,0,0,0,1,0,0,0\n", 2, "no material named 'steel'"},
        {"empty file", "", 1, "no header row"},
        {"header only", header, 0, "holds no grains"},
    };
    for (const Case& c : cases) {
        const Folder f(c.packing);
        try {
            readSceneFile(f.scene);
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const Error& e) {
            const std::string where = c.line > 0
                                          ? f.dir.file("packing.csv") + ":" + std::to_string(c.line)
                                          : f.scene + ":" + std::to_string(lineOf(sceneText(), "file = "));
            EXPECT_EQ(e.where(), where) << c.what << ": " << e.what();
            EXPECT_NE(e.problem().find(c.message), std::string::npos) << c.what << ": " << e.what();
            EXPECT_FALSE(e.fix().empty()) << c.what;
        }
    }
    // A file that is not there.
    ScratchDir dir;
    const std::string scene = dir.file("scene.toml");
    std::ofstream(scene) << sceneText();
    try {
        readSceneFile(scene);
        ADD_FAILURE() << "a missing grain file was accepted";
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("cannot read"), std::string::npos) << e.what();
        EXPECT_EQ(e.where(), scene + ":" + std::to_string(lineOf(sceneText(), "file = ")));
    }
}

// Grains "a" (R = 2 at the origin) and "b" (R = 1.5 at x = 3.3): their surfaces overlap by
// 2 + 1.5 − 3.3 = 0.2, more than the default allowance (5 % of the smaller bounding radius,
// 0.075): refused, naming both lines and a depth near 0.2 (nodes of the 200–300-node spheres
// sit a little off the deepest point, and φ is trilinear on voxels of 0.25: ±0.05). With
// max_overlap = 0.3 it is accepted; touching grains (0.01 apart) always are.
TEST(GrainsCsv, OverlappingGrainsAreRefusedWithTheirLinesAndDepth)
{
    const std::string header = "name,asset,x,y,z,qw,qx,qy,qz\n";
    const std::string overlapping = header + "a,big,0,0,0,1,0,0,0\nb,small,3.3,0,0,1,0,0,0\n";
    {
        const Folder f(overlapping);
        const Scene s = readSceneFile(f.scene);
        std::vector<std::string> warnings;
        try {
            buildWorld(s, warnings);
            ADD_FAILURE() << "overlapping grains were accepted";
        } catch (const Error& e) {
            const std::string msg = e.problem();
            EXPECT_EQ(e.where(), f.dir.file("packing.csv") + ":2") << e.what();
            EXPECT_NE(msg.find("'a' (" + f.dir.file("packing.csv") + ":2)"), std::string::npos) << msg;
            EXPECT_NE(msg.find("'b' (" + f.dir.file("packing.csv") + ":3)"), std::string::npos) << msg;
            const size_t at = msg.find("overlap by ");
            ASSERT_NE(at, std::string::npos) << msg;
            const double depth = std::stod(msg.substr(at + 11));
            EXPECT_NEAR(depth, 0.2, 0.05) << msg;
            EXPECT_NE(e.fix().find("max_overlap"), std::string::npos);
        }
    }
    {
        const Folder f(overlapping, "max_overlap = 0.3\n");
        std::vector<std::string> warnings;
        EXPECT_EQ(buildWorld(readSceneFile(f.scene), warnings).grains.size(), 3u);
    }
    {
        const Folder f(header + "a,big,0,0,0,1,0,0,0\nb,small,3.51,0,0,1,0,0,0\n");
        std::vector<std::string> warnings;
        EXPECT_EQ(buildWorld(readSceneFile(f.scene), warnings).grains.size(), 3u);
    }
}
