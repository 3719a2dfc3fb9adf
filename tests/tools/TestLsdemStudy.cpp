// lsdem-study two-spheres as a user runs it: a small study end to end, and bad input refused
// with a clear message, a non-zero exit and no results written.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>

using lsdem::test::runCommand;

namespace {

const std::string kStudy = LSDEM_STUDY_EXE;

int countLines(const std::string& path)
{
    std::ifstream in(path);
    int n = 0;
    for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
    return n;
}

} // namespace

TEST(LsdemStudy, SmallTwoSpheresRunWritesTheCsv)
{
    lsdem::test::ScratchDir dir;
    const auto r = runCommand(kStudy + " two-spheres --nodes 300 600 --steps 4 --orientations 2"
                              " --voxel 0.1 --no-plots -q --out " + dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // Header + 2 formulations x 2 node counts x 5 δ values (no k series: 8000 is not run...
    // the count nearest 8000 is 600, which gets the 4-value k series).
    const int rows = countLines(dir.file("out/two_spheres.csv")) - 1;
    EXPECT_EQ(rows, 2 * (1 + 4) * 5);
    EXPECT_NE(r.output.find("node checks"), std::string::npos) << r.output;
}

TEST(LsdemStudy, RefusesBadInput)
{
    lsdem::test::ScratchDir dir;
    const std::string out = dir.file("out");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--nodes 0", "--nodes"},
        {"--nodes -100", "--nodes"},
        {"--radius 0", "--radius"},
        {"--radius -5", "--radius"},
        {"--delta-max 0", "--delta-max"},
        {"--delta-max -0.1", "--delta-max"},
        {"--kn 0", "--kn"},
        {"--kn -1e3", "--kn"},
        {"--voxel nan", "--voxel"},
        {"--formulation magic", "magic"},
        {"--orientations 0", "--orientations"},
        {"--colour red", "--colour"},
    };
    for (const auto& [args, mustSay] : cases) {
        const auto r = runCommand(kStudy + " two-spheres " + args + " --out " + out);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_NE(r.output.find(mustSay), std::string::npos) << args << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(out + "/two_spheres.csv")) << args;
    }
    // An output folder that cannot be made (a file is in the way).
    std::ofstream(dir.file("blocker")) << "x";
    const auto r = runCommand(kStudy + " two-spheres --out " + dir.file("blocker") + "/sub");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("blocker"), std::string::npos) << r.output;
    const auto unknown = runCommand(kStudy + " three-spheres");
    EXPECT_NE(unknown.exitCode, 0);
    EXPECT_NE(unknown.output.find("three-spheres"), std::string::npos);
}
