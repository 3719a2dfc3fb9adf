// lsdem-study two-spheres as a user runs it: a small study end to end, and bad input refused
// with a clear message, a non-zero exit and no results written.
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/core/CsvText.h"
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

// A volume row is compared with the volume law's own limit, kv·∫ d dA (it was the adapted
// law's, 0.34 % lower at δ = 0.1 mm), and the summary gives its error as for adapted rows.
TEST(LsdemStudy, VolumeRowsAreComparedWithTheVolumeLawsLimit)
{
    lsdem::test::ScratchDir dir;
    const auto r = runCommand(kStudy + " two-spheres --formulation volume --nodes 300 --steps 1"
                              " --orientations 1 --voxel 0.2 --no-plots --out " + dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("vs its exact"), std::string::npos) << r.output;
    std::ifstream in(dir.file("out/two_spheres.csv"));
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty() && line[0] != '#') last = line;
    // formulation,nodes,nodes_actual,kn,voxel,delta,P,P_std,P_min,P_max,P_exact,kn_unit,converges
    std::vector<std::string> f;
    ASSERT_TRUE(lsdem::splitCsvRecord(last, f)) << last;
    ASSERT_EQ(f.size(), 13u) << last;
    EXPECT_EQ(f[11], "N/mm³");  // kv: a force per overlap volume
    EXPECT_EQ(f[12], "1");
    EXPECT_EQ(f[0], "volume");
    const double kv = std::stod(f[3]), delta = std::stod(f[5]), exact = std::stod(f[10]);
    EXPECT_EQ(delta, 0.1);
    EXPECT_NEAR(exact / lsdem::exactSphereVolumeForce(5.0, delta, kv), 1.0, 1e-9) << last;
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

// The plot scripts are found from the program's own folder, <exe>/../share/lsdem/plots (the
// build keeps a copy there, as an installation does), or in $LSDEM_PLOT_DIR; no source path is
// compiled into the program.
TEST(LsdemStudy, FindsThePlotScriptsBesideItself)
{
    const std::filesystem::path exe = kStudy;
    const std::filesystem::path beside = exe.parent_path().parent_path() / "share/lsdem/plots";
    for (const char* script : {"two_spheres.py", "cube27.py", "slab.py", "plotting.py"})
        EXPECT_TRUE(std::filesystem::is_regular_file(beside / script)) << beside / script;
    {
        std::ifstream in(exe, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(bytes.find(LSDEM_SOURCE_DIR "/tools/plots"), std::string::npos);
    }

    // A stand-in script in a folder named by LSDEM_PLOT_DIR: it writes down its arguments.
    lsdem::test::ScratchDir dir;
    std::filesystem::create_directory(dir.file("plots"));
    std::ofstream(dir.file("plots/two_spheres.py"))
        << "import pathlib, sys\n"
           "pathlib.Path(sys.argv[2], 'plotted.txt').write_text(' '.join(sys.argv[1:]))\n";
    const std::string tiny = " two-spheres --nodes 300 --steps 1 --orientations 1 --voxel 0.2"
                             " --formulation adapted --k-factors 1 -q --out ";
    const auto r = runCommand("LSDEM_PLOT_DIR=" + dir.file("plots") + " " + kStudy + tiny +
                              dir.file("a"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    std::ifstream plotted(dir.file("a/plotted.txt"));
    std::string arguments;
    std::getline(plotted, arguments);
    EXPECT_EQ(arguments, dir.file("a/two_spheres.csv") + " " + dir.file("a"));

    // A folder without the script: the data is complete, a warning names the folder, exit 4.
    const auto missing = runCommand("LSDEM_PLOT_DIR=" + dir.file("nowhere") + " " + kStudy +
                                    tiny + dir.file("b"));
    EXPECT_EQ(missing.exitCode, 4) << missing.output;
    EXPECT_NE(missing.output.find(dir.file("nowhere")), std::string::npos) << missing.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("b/two_spheres.csv")));
}

namespace {

/// @a text as one word for the shell that runCommand starts.
std::string shellQuoted(const std::string& text)
{
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

bool hasMatplotlib()
{
    return runCommand("/usr/bin/python3 -c 'import matplotlib'").exitCode == 0;
}

} // namespace

// The plot script gets the --out folder as one argument, whatever it is called: no shell sits
// between them to run what the name holds (it once did: a quote ended the argument).
TEST(LsdemStudy, PlotsIntoAFolderOfAnyName)
{
    lsdem::test::ScratchDir dir;
    const std::string out = "it's a run; touch INJECTED; $(touch INJECTED2) `touch INJECTED3`";
    const auto r = runCommand("cd " + dir.path().string() + " && " + kStudy +
                              " two-spheres --nodes 100 --voxel 0.5 --orientations 1 --steps 2"
                              " --formulation adapted -q --out " + shellQuoted(out));
    for (const char* marker : {"INJECTED", "INJECTED2", "INJECTED3"})
        EXPECT_FALSE(std::filesystem::exists(dir.file(marker))) << marker << ": " << r.output;
    ASSERT_TRUE(std::filesystem::exists(dir.file(out + "/two_spheres.csv"))) << r.output;
    if (!hasMatplotlib())
        GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib: the plots are not drawn";
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file(out + "/two_spheres_convergence.png")))
        << r.output;
}

// The triaxial study's plots read its CSVs as the study writes them (a text column added to
// triaxial_runs.csv once broke them, seen only in the demo): a small run draws both figures.
TEST(LsdemStudy, TriaxialPlotsReadTheStudysFiles)
{
    if (!hasMatplotlib())
        GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib: the plots are not drawn";
    lsdem::test::ScratchDir dir;
    const auto r = runCommand("timeout 120 " + kStudy + " triaxial --meshes " LSDEM_SOURCE_DIR
                              "/assets/meshes/sand --grains 8 --sdps 0.2 --formulation adapted "
                              "--axial-strain 0.01 --records 2 --path unload-reload -q --out " +
                              dir.file("out"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    for (const char* png : {"triaxial_curves.png", "triaxial_friction_angles.png"})
        EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("out/") + png))) << png;
}

// A plot script that fails for its own reasons is named with its exit status, not blamed on a
// missing matplotlib; the data files are complete and the exit code is 4.
TEST(LsdemStudy, SaysHowAPlotScriptFailed)
{
    if (!hasMatplotlib())
        GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib: that is the message then";
    lsdem::test::ScratchDir dir;
    std::filesystem::create_directory(dir.file("plots"));
    std::ofstream(dir.file("plots/two_spheres.py")) << "import sys\nsys.exit(7)\n";
    const auto r = runCommand("LSDEM_PLOT_DIR=" + dir.file("plots") + " " + kStudy +
                              " two-spheres --nodes 100 --voxel 0.5 --orientations 1 --steps 2"
                              " --formulation adapted -q --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("exit status 7"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(dir.file("plots/two_spheres.py")), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/two_spheres.csv")));
}

// Input that only a bake, a plan or the mesh search refuses (after the options' own checks)
// leaves no empty --out folder behind: the folder is made when the first result is written.
// A folder the user had already is kept as it was.
TEST(LsdemStudy, InputRefusedLateLeavesNoOutputFolder)
{
    lsdem::test::ScratchDir dir;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"two-spheres --voxel 100", "voxel size 100"},
        {"two-spheres --voxel 1e-5", "voxel size 1e-05"},
        {"cube27 --kn 1e305", "the stiffness 1e+305 (--kn"},
        {"triaxial --meshes /nonexistent.obj", "/nonexistent.obj"},
    };
    int index = 0;
    for (const auto& [args, mustSay] : cases) {
        const std::string out = dir.file("new" + std::to_string(index++) + "/out");
        const auto r = runCommand(kStudy + " " + args + " -q --out " + out);
        EXPECT_EQ(r.exitCode, 1) << args << ": " << r.output;
        EXPECT_NE(r.output.find(mustSay), std::string::npos) << args << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;
        EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(out).parent_path())) << args;
    }
    std::filesystem::create_directory(dir.file("mine"));
    const auto r = runCommand(kStudy + " two-spheres --voxel 100 -q --out " + dir.file("mine"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("mine")));
}

// A second run into the same --out removes what the first run wrote and this one does not
// (here: the plots of a formulation no longer run), so the folder never shows plots beside a
// CSV without their rows; files the study does not write are kept.
TEST(LsdemStudy, RerunRemovesTheEarlierRunsFilesOnly)
{
    lsdem::test::ScratchDir dir;
    const std::string out = dir.file("out");
    const std::string tiny = " two-spheres --nodes 100 --voxel 0.5 --orientations 1 --steps 2 -q";
    const auto first = runCommand(kStudy + tiny + " --formulation original --out " + out);
    const std::string stale = out + "/two_spheres_fig1_original_by_nodes.png";
    if (!hasMatplotlib()) std::ofstream(stale) << "as the first run's plots would be";
    ASSERT_TRUE(std::filesystem::exists(stale)) << first.output;
    std::ofstream(out + "/notes.txt") << "the user's";
    std::ofstream(out + "/two_spheres_notes.txt") << "the user's too";

    const auto second =
        runCommand(kStudy + tiny + " --formulation volume --no-plots --out " + out);
    ASSERT_EQ(second.exitCode, 0) << second.output;
    EXPECT_FALSE(std::filesystem::exists(stale)) << second.output;
    EXPECT_FALSE(std::filesystem::exists(out + "/two_spheres_convergence.png"));
    EXPECT_EQ(lsdem::test::readFile(out + "/notes.txt"), "the user's");
    EXPECT_EQ(lsdem::test::readFile(out + "/two_spheres_notes.txt"), "the user's too");
    EXPECT_NE(lsdem::test::readFile(out + "/two_spheres.csv").find("volume"), std::string::npos);
    EXPECT_EQ(lsdem::test::readFile(out + "/two_spheres.csv").find("original"), std::string::npos);
    // The removal is reported, but not under -q (the summary only).
    EXPECT_EQ(second.output.find("of an earlier run"), std::string::npos) << second.output;
    const auto loud = runCommand(kStudy + " two-spheres --nodes 100 --voxel 0.5 --orientations 1 "
                                          "--steps 2 --formulation volume --no-plots --out " + out);
    ASSERT_EQ(loud.exitCode, 0) << loud.output;
    EXPECT_NE(loud.output.find("of an earlier run from " + out), std::string::npos) << loud.output;

    // Refused input removes nothing: the earlier results stay until a run replaces them.
    const auto refused = runCommand(kStudy + tiny + " --voxel 100 --out " + out);
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(lsdem::test::readFile(out + "/two_spheres.csv").find("volume"), std::string::npos);
}
