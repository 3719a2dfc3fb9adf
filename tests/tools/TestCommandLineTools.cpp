// The real programs, lsdem-bake and lsdem-inspect, on good and bad input: every bad input
// gets a message naming the file or option, a non-zero exit, and no output file.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/MeshIO.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace lsdem;
using lsdem::test::runCommand;

namespace {

const std::string kBake = LSDEM_BAKE_EXE;
const std::string kInspect = LSDEM_INSPECT_EXE;

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

} // namespace

TEST(CommandLineTools, BakeThenInspectAnAnalyticSphere)
{
    test::ScratchDir dir;
    const std::string out = dir.file("sphere.vdb");
    auto bake = runCommand(kBake + " --sphere 1 --voxel 0.1 --node-spacing 0.25 -o " + out);
    ASSERT_EQ(bake.exitCode, 0) << bake.output;
    auto summary = runCommand(kInspect + " " + out);
    ASSERT_EQ(summary.exitCode, 0) << summary.output;
    EXPECT_TRUE(contains(summary.output, "lsdem grain asset"));
    auto json = runCommand(kInspect + " " + out + " --json");
    ASSERT_EQ(json.exitCode, 0) << json.output;
    EXPECT_TRUE(contains(json.output, "\"node_count\""));
    auto sample = runCommand(kInspect + " " + out + " --sample 0 0 0");
    ASSERT_EQ(sample.exitCode, 0) << sample.output;
    EXPECT_TRUE(contains(sample.output, "= -1")) << sample.output;  // φ(centre) = -R
    auto slice = runCommand(kInspect + " " + out + " --slice z=0 --png " + dir.file("z.png") +
                            " --mesh " + dir.file("iso.obj"));
    ASSERT_EQ(slice.exitCode, 0) << slice.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("z.png")));
    EXPECT_GT(readMesh(dir.file("iso.obj")).triangles.size(), 100u);
}

TEST(CommandLineTools, VdbPrintOpensAnAsset)
{
    if (runCommand("command -v vdb_print").exitCode != 0) GTEST_SKIP() << "no vdb_print";
    test::ScratchDir dir;
    const std::string out = dir.file("box.vdb");
    ASSERT_EQ(runCommand(kBake + " --box 1 2 3 --voxel 0.1 --node-spacing 0.3 -o " + out).exitCode, 0);
    auto print = runCommand("vdb_print " + out);
    EXPECT_EQ(print.exitCode, 0) << print.output;
    EXPECT_TRUE(contains(print.output, "phi")) << print.output;
    EXPECT_TRUE(contains(print.output, "nodes")) << print.output;
}

struct BadCase
{
    const char* name;
    std::string setup;       ///< shell command run first in the scratch folder (may be empty)
    std::string arguments;   ///< lsdem-bake arguments; $D is the scratch folder
    std::string mustSay;     ///< a piece of the message
};

TEST(CommandLineTools, BakeRefusesBadInputCleanly)
{
    test::ScratchDir dir;
    const std::string d = dir.path().string();
    // An open cube (one triangle missing), a NaN vertex, an inside-out-only-in-part mesh.
    writeMesh(AnalyticShape::box(1, 1, 1).surfaceMesh(1.0), d + "/cube.obj");
    {
        std::ifstream in(d + "/cube.obj");
        std::string all((std::istreambuf_iterator<char>(in)), {});
        std::ofstream(d + "/open.obj") << all.substr(0, all.rfind("f "));
        std::string nan = all;
        nan.replace(nan.find("v ") + 2, 1, "nan ");
        std::ofstream(d + "/nan.obj") << nan;
    }
    std::ofstream(d + "/garbage.stl") << "solid x\n this is not really an stl\n";
    std::ofstream(d + "/empty.obj") << "# nothing here\n";
    std::ofstream(d + "/points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    std::ofstream(d + "/mesh.xyz") << "1 2 3\n";

    const std::vector<BadCase> cases = {
        {"missing mesh", "", "$D/none.stl --voxel 0.1 --node-spacing 0.2", "none.stl"},
        {"unknown format", "", "$D/mesh.xyz --voxel 0.1 --node-spacing 0.2", "mesh.xyz"},
        {"garbage stl", "", "$D/garbage.stl --voxel 0.1 --node-spacing 0.2", "garbage.stl"},
        {"empty mesh", "", "$D/empty.obj --voxel 0.1 --node-spacing 0.2", "empty.obj"},
        {"points only", "", "$D/points.obj --voxel 0.1 --node-spacing 0.2", "points.obj"},
        {"open surface", "", "$D/open.obj --voxel 0.05 --node-spacing 0.2", "boundary edge"},
        {"nan vertex", "", "$D/nan.obj --voxel 0.05 --node-spacing 0.2", "nan.obj"},
        {"zero voxel", "", "--sphere 1 --voxel 0 --node-spacing 0.2", "voxel"},
        {"negative voxel", "", "--sphere 1 --voxel -0.1 --node-spacing 0.2", "voxel"},
        {"nan voxel", "", "--sphere 1 --voxel nan --node-spacing 0.2", "--voxel"},
        {"voxel larger than shape", "", "--sphere 1 --voxel 3 --node-spacing 0.2", "too coarse"},
        {"grid over budget", "", "--sphere 1 --voxel 0.0005 --node-spacing 0.2", "memory budget"},
        {"negative radius", "", "--sphere -1 --voxel 0.1 --node-spacing 0.2", "positive"},
        {"zero spacing", "", "--sphere 1 --voxel 0.1 --node-spacing 0", "spacing"},
        {"too few nodes", "", "--sphere 1 --voxel 0.1 --nodes 2", "--nodes"},
        {"bad area rule", "", "--sphere 1 --voxel 0.1 --nodes 100 --areas maybe", "--areas"},
        {"unknown option", "", "--sphere 1 --voxel 0.1 --nodes 100 --colour red", "--colour"},
        {"no placement", "", "--sphere 1 --voxel 0.1", "--node-spacing"},
        {"mesh nodes, no mesh", "", "--sphere 1 --voxel 0.1 --mesh-nodes", "mesh"},
        {"two placements", "", "--sphere 1 --voxel 0.1 --nodes 100 --node-spacing 0.1", "one of"},
        {"box missing edge", "", "--box 1 2 --voxel 0.1 --nodes 100", "--box"},
    };
    for (const BadCase& c : cases) {
        std::string args = c.arguments;
        if (args.find("$D") != std::string::npos) args.replace(args.find("$D"), 2, d);
        const std::string out = d + "/out.vdb";
        const auto result = runCommand(kBake + " " + args + " -o " + out);
        EXPECT_NE(result.exitCode, 0) << c.name << ": " << result.output;
        EXPECT_TRUE(contains(result.output, c.mustSay)) << c.name << ": " << result.output;
        EXPECT_TRUE(contains(result.output, "error")) << c.name << ": " << result.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
    }
    // An unwritable output folder.
    const auto result =
        runCommand(kBake + " --sphere 1 --voxel 0.1 --nodes 100 -o /nonexistent-lsdem/x.vdb");
    EXPECT_NE(result.exitCode, 0);
    EXPECT_TRUE(contains(result.output, "nonexistent-lsdem")) << result.output;
    // Nothing but the inputs is left in the folder: no temporaries.
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        EXPECT_FALSE(contains(e.path().filename().string(), ".tmp")) << e.path();
}

TEST(CommandLineTools, InspectRefusesBadFilesCleanly)
{
    test::ScratchDir dir;
    std::ofstream(dir.file("junk.vdb")) << "not a vdb";
    for (const std::string& file : {dir.file("junk.vdb"), dir.file("missing.vdb")}) {
        const auto result = runCommand(kInspect + " " + file);
        EXPECT_NE(result.exitCode, 0);
        EXPECT_TRUE(contains(result.output, file)) << result.output;
    }
    const auto slice = runCommand(kInspect + " " + dir.file("junk.vdb") + " --slice q=1 --png x.png");
    EXPECT_NE(slice.exitCode, 0);
    EXPECT_TRUE(contains(slice.output, "--slice")) << slice.output;
}
