// lsdem-pack through the real program, and its packing used as a user would: read by a scene
// ([[grain_files]]) with a servo wall on top, run by lsdem-run, whose boundary CSV then holds
// the wall's stress; a cylinder; a catalogue baked by lsdem-bake --out-dir, packed and read
// back by a scene's [asset_sets]. A count that cannot fit and bad options exit 1 and write
// nothing.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

using namespace lsdem::test;

namespace {

const std::string kPack = LSDEM_PACK_EXE;

struct Assets
{
    ScratchDir dir;
    Assets()
    {
        const CommandResult bake = runCommand(std::string(LSDEM_BAKE_EXE) +
                                              " --sphere 1 --voxel 0.1 --nodes 150 -o " +
                                              dir.file("ball.vdb"));
        EXPECT_EQ(bake.exitCode, 0) << bake.output;
    }
};

} // namespace

TEST(LsdemPack, PacksAndTheSceneRunsWithAServoLid)
{
    const Assets a;
    const std::string csv = a.dir.file("packing.csv");
    const CommandResult pack = runCommand(kPack + " " + a.dir.file("ball.vdb") +
                                          " --count 4 --box 0 0 0 4.5 4.5 5 --seed 2 -o " + csv);
    ASSERT_EQ(pack.exitCode, 0) << pack.output;
    EXPECT_NE(pack.output.find("packed 4 grains"), std::string::npos) << pack.output;
    EXPECT_EQ(readFile(csv).rfind("asset,x,y,z,qw,qx,qy,qz\nball,", 0), 0u) << readFile(csv);

    // The lid starts above the packing and comes down at its limit speed until it presses.
    std::ofstream(a.dir.file("scene.toml")) << R"([assets.ball]
file = "ball.vdb"
[materials.sand]
density = 2.65e-9
[[contacts]]
materials = ["sand", "sand"]
normal_stiffness = 1e3
restitution = 0.5
[[grain_files]]
file = "packing.csv"
material = "sand"
[[boundaries]]
name = "floor"
type = "plane"
material = "sand"
point = [0, 0, 0]
normal = [0, 0, 1]
[[boundaries]]
name = "lid"
type = "plane"
material = "sand"
point = [0, 0, 5]
normal = [0, 0, -1]
stress = 0.01
area = 20.25
max_speed = 100
[simulation]
time_step = 1e-6
end_steps = 400
[output]
history_every = 100
)";
    const CommandResult run = runCommand(std::string(LSDEM_RUN_EXE) + " " +
                                         a.dir.file("scene.toml") + " --out " +
                                         a.dir.file("out") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    std::istringstream lid(readFile(a.dir.file("out/boundary_lid.csv")));
    std::string header, row;
    std::getline(lid, header);
    EXPECT_EQ(header, "step,time,ux,uy,uz,fx,fy,fz,px,py,pz,area,stress,target_stress,speed");
    ASSERT_TRUE(std::getline(lid, row) && std::getline(lid, row));  // step 100
    // Not touching yet: it moves at the limit speed, 100·1e-6 per step, towards the grains.
    std::vector<double> v;
    std::istringstream fields(row);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 15u) << row;
    EXPECT_EQ(v[0], 100.0);
    EXPECT_NEAR(v[4], -0.01, 1e-12) << row;       // uz
    EXPECT_NEAR(v[10], 5.0 - 0.01, 1e-12) << row;  // pz
    EXPECT_EQ(v[11], 20.25);                       // area
    EXPECT_EQ(v[12], 0.0);                         // stress: not touching
    EXPECT_EQ(v[13], 0.01);                        // target
    EXPECT_EQ(v[14], 100.0);                       // speed towards the grains
    EXPECT_EQ(readFile(a.dir.file("out/boundary_floor.csv")).substr(0, 28),
              "step,time,ux,uy,uz,fx,fy,fz\n");
}

TEST(LsdemPack, ACountThatCannotFitExitsWithWhatDid)
{
    const Assets a;
    const std::string csv = a.dir.file("packing.csv");
    const CommandResult r = runCommand(kPack + " " + a.dir.file("ball.vdb") +
                                       " --count 5 --box 0 0 0 2.5 2.5 3 -o " + csv);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("only 1 of 5 grains fit"), std::string::npos) << r.output;
    // One ball of radius 1 in 2.5 × 2.5 × 3: (4π/3)/18.75 = 0.2234.
    EXPECT_NE(r.output.find("solid fraction 0.223 "), std::string::npos) << r.output;
    EXPECT_FALSE(std::ifstream(csv).good());
}

TEST(LsdemPack, BadOptionsExitOne)
{
    const Assets a;
    const std::string ball = a.dir.file("ball.vdb");
    std::ofstream(a.dir.file("cat.csv")) << "name,asset\nball,ball.vdb\n";
    std::ofstream(a.dir.file("bad.csv")) << "name,asset\nball,none.vdb\n";
    for (const std::string& args :
         {ball + " --count 4 -o x.csv", ball + " --box 0 0 0 5 5 5 --count 4",
          ball + " --box 0 0 0 5 5 5 --count 0 -o x.csv",
          ball + " --box 0 0 0 5 5 5 --count 4 --fractions 1 2 -o x.csv",
          a.dir.file("missing.vdb") + " --box 0 0 0 5 5 5 --count 4 -o x.csv",
          ball + " --cylinder 0 0 3 0 --count 4 -o x.csv"}) {
        const CommandResult r = runCommand("cd " + a.dir.path().string() + " && " + kPack + " " + args);
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("lsdem-pack: error:"), std::string::npos) << r.output;
    }
    // The container and the catalogue: the message names the option or the file, and a fix.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {ball + " --box 0 0 0 5 5 5 --cylinder 0 0 3 0 5 --count 4 -o x.csv", "both --box and --cylinder"},
        {ball + " --count 4 -o x.csv", "no container given"},
        {ball + " --cylinder 0 0 0 0 5 --count 4 -o x.csv", "--cylinder: the radius must be > 0"},
        {ball + " --cylinder 0 0 3 5 5 --count 4 -o x.csv", "--cylinder: Z1 must exceed Z0"},
        {ball + " --cylinder 0 0 0.9 0 5 --count 4 -o x.csv", "does not fit in the cylinder"},
        {ball + " --catalog cat.csv --set s --box 0 0 0 5 5 5 --count 4 -o x.csv", "both asset files and --catalog"},
        {"--catalog cat.csv --box 0 0 0 5 5 5 --count 4 -o x.csv", "--catalog needs --set NAME"},
        {"--set s --box 0 0 0 5 5 5 --count 4 -o x.csv", "no --catalog is given"},
        {"--catalog nowhere.csv --set s --box 0 0 0 5 5 5 --count 4 -o x.csv", "nowhere.csv: catalogue not found"},
        {"--catalog cat.csv --set s --fractions 1 2 3 --box 0 0 0 5 5 5 --count 4 -o x.csv", "--fractions has 3 values for 1 assets of the catalogue cat.csv"},
        {"--catalog cat.csv --set s --names a --box 0 0 0 5 5 5 --count 4 -o x.csv", "--names is for asset files"},
        {"--catalog cat.csv --set a/b --box 0 0 0 5 5 5 --count 4 -o x.csv", "'a/b' must be non-empty and hold no '/'"},
        {"--catalog bad.csv --set s --box 0 0 0 5 5 5 --count 4 -o x.csv", "bad.csv: asset 'ball': file not found: none.vdb"},
        {"--catalog cat.csv --set s --cylinder 0 0 1.2 0 3 --count 4 -o x.csv", "only 1 of 4 grains fit in the cylinder"},
        {ball + " --box 0 0 0 5 5 5 --count 4 --friction -1 -o x.csv", "--friction must be a finite number >= 0, got -1"},
        {ball + " --box 0 0 0 5 5 5 --count 4 --settle -1 -o x.csv", "--settle must be a finite number > 0, got -1"},
        // Found by review: TBB ran out of memory starting them (exit 3).
        {ball + " --box 0 0 0 5 5 5 --count 4 --threads 99999999999 -o x.csv", "--threads wants 0 (all cores) or a number up to 1024, got 99999999999"},
        {ball + " --box 0 0 0 5 5 5 -o x.csv", "--count is required"},
        // The output folder is checked before anything is read (the missing asset is not).
        {"missing.vdb --box 0 0 0 5 5 5 --count 4 -o nowhere/x.csv", "nowhere/x.csv"},
    };
    for (const auto& [args, message] : cases) {
        const CommandResult r = runCommand("cd " + a.dir.path().string() + " && " + kPack + " " + args);
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("lsdem-pack: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("fix:"), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_FALSE(std::ifstream(a.dir.file("x.csv")).good());
}

// Found by review: `lsdem-pack cat/g.vdb ... -o cat/g.vdb` overwrote the asset with the CSV.
TEST(LsdemPack, AnOutputThatIsAnInputIsRefused)
{
    const Assets a;
    const std::string ball = a.dir.file("ball.vdb");
    const std::string asset = readFile(ball);
    std::ofstream(a.dir.file("cat.csv")) << "name,asset\nball,ball.vdb\n";
    // An asset the catalogue lists, however spelt (-o over one of them replaced it).
    std::filesystem::create_symlink(ball, a.dir.file("link.vdb"));
    const std::string catalogue = "--catalog cat.csv --set s --box 0 0 0 5 5 5 --count 4 -o ";
    for (const std::string& args : {ball + " --box 0 0 0 5 5 5 --count 4 -o " + ball,
                                    catalogue + "./cat.csv", catalogue + "ball.vdb",
                                    catalogue + "link.vdb", catalogue + ball}) {
        const CommandResult r =
            runCommand("cd " + a.dir.path().string() + " && " + kPack + " " + args);
        EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("is also an input"), std::string::npos) << r.output;
    }
    EXPECT_TRUE(readFile(ball) == asset) << "the asset was changed";
    EXPECT_EQ(readFile(a.dir.file("cat.csv")), "name,asset\nball,ball.vdb\n");
}

// Found by review: the help showed "--count INT=0", a count it refuses.
TEST(LsdemPack, HelpShowsTheCountAsRequired)
{
    const CommandResult r = runCommand(kPack + " --help");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("--count INT REQUIRED"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("--count INT="), std::string::npos) << r.output;
}

// Found by review: fractions of 1e308 each added up to inf, and the shares became NaN (exit 3,
// an internal error). Only their ratio counts.
TEST(LsdemPack, HugeFractionsShareTheCountByTheirRatio)
{
    const Assets a;
    std::filesystem::copy_file(a.dir.file("ball.vdb"), a.dir.file("other.vdb"));
    const std::string csv = a.dir.file("packing.csv");
    const CommandResult r = runCommand(kPack + " " + a.dir.file("ball.vdb") + " " +
                                       a.dir.file("other.vdb") +
                                       " --fractions 1e308 1e308 --count 2 --box 0 0 0 4.5 4.5 5 "
                                       "-o " + csv);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string table = readFile(csv);
    EXPECT_NE(table.find("\nball,"), std::string::npos) << table;
    EXPECT_NE(table.find("\nother,"), std::string::npos) << table;
}

// A list option given again keeps its last list, as a single value does (--names here).
TEST(LsdemPack, ARepeatedNamesOptionKeepsItsLastList)
{
    const Assets a;
    const std::string csv = a.dir.file("packing.csv");
    const CommandResult r =
        runCommand(kPack + " " + a.dir.file("ball.vdb") + " --names first --names second " +
                   "--count 1 --box 0 0 0 4.5 4.5 5 -o " + csv);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string table = readFile(csv);
    EXPECT_NE(table.find("\nsecond,"), std::string::npos) << table;
    EXPECT_EQ(table.find("first"), std::string::npos) << table;
}

TEST(LsdemPack, FillsACylinder)
{
    const Assets a;
    const std::string csv = a.dir.file("packing.csv");
    const std::string command = kPack + " " + a.dir.file("ball.vdb") +
                                " --count 4 --cylinder 1 1 2.4 0 6 --seed 3 -o ";
    const CommandResult pack = runCommand(command + csv + " --threads 2");
    ASSERT_EQ(pack.exitCode, 0) << pack.output;
    // The same file byte for byte on one thread.
    const CommandResult serial = runCommand(command + a.dir.file("serial.csv") + " --threads 1");
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    EXPECT_EQ(readFile(a.dir.file("serial.csv")), readFile(csv));
    EXPECT_NE(pack.output.find("packed 4 grains"), std::string::npos) << pack.output;
    std::istringstream rows(readFile(csv));
    std::string row;
    std::getline(rows, row);
    int count = 0;
    for (; std::getline(rows, row); ++count) {
        std::vector<double> v;
        std::istringstream fields(row.substr(row.find(',') + 1));
        for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
        ASSERT_EQ(v.size(), 7u) << row;
        // A ball of radius 1 inside the cylinder of radius 2.4 about (1, 1), up to the wall's
        // contact overlap (about 1 % of the radius by design; 3 % allowed).
        EXPECT_LT(std::hypot(v[0] - 1.0, v[1] - 1.0), 2.4 - 1.0 + 0.03) << row;
        EXPECT_GT(v[2], 1.0 - 0.03) << row;
    }
    EXPECT_EQ(count, 4);
}

// The user's path for many shapes: generate meshes, bake them into a catalogue, pack every
// asset of the catalogue, and run a scene that reads the catalogue as an asset set and the
// packing as a grain table.
TEST(LsdemPack, PacksACatalogueThatASceneReadsAsAnAssetSet)
{
    ScratchDir dir;
    ASSERT_EQ(runCommand(std::string(LSDEM_GRAINS_EXE) + " --count 2 --triangles 320 --max-degree 6 "
                         "--size 2 -q --out-dir " + dir.file("scans"))
                  .exitCode,
              0);
    const CommandResult bake = runCommand(std::string(LSDEM_BAKE_EXE) + " " + dir.file("scans") +
                                          "/*.stl --out-dir " + dir.file("assets") +
                                          " --voxel-per-size 0.08 --nodes 150 -q");
    ASSERT_EQ(bake.exitCode, 0) << bake.output;
    const std::string csv = dir.file("packing.csv");
    const CommandResult pack =
        runCommand(kPack + " --catalog " + dir.file("assets/catalog.csv") +
                   " --set sand --count 6 --box 0 0 0 6 6 8 --settle 1e-3 -o " + csv);
    ASSERT_EQ(pack.exitCode, 0) << pack.output;
    const std::string table = readFile(csv);
    // Equal shares of the catalogue's two assets, named as the set names them.
    int first = 0, second = 0;
    for (size_t at = 0; (at = table.find("\nsand/grain_000", at)) != std::string::npos; ++at)
        (table[at + 15] == '0' ? first : second) += 1;
    EXPECT_EQ(first, 3) << table;
    EXPECT_EQ(second, 3) << table;

    std::ofstream(dir.file("scene.toml")) << R"([asset_sets.sand]
catalog = "assets/catalog.csv"
[materials.sand]
density = 2.65e-9
[[contacts]]
materials = ["sand", "sand"]
normal_stiffness = 1e3
[[grain_files]]
file = "packing.csv"
material = "sand"
[[boundaries]]
name = "floor"
type = "plane"
material = "sand"
point = [0, 0, 0]
normal = [0, 0, 1]
[simulation]
time_step = 1e-6
end_steps = 10
)";
    const CommandResult run = runCommand(std::string(LSDEM_RUN_EXE) + " " +
                                         dir.file("scene.toml") + " --out " + dir.file("out") +
                                         " --quiet");
    EXPECT_EQ(run.exitCode, 0) << run.output;
}
