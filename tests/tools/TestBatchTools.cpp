// lsdem-grains and lsdem-bake --out-dir as a user runs them: generated files are the same
// bytes for the same seed and pass the mesh checks; a batch with a corrupt file bakes the
// others, lists the failure and exits 4; the catalogue's values are lsdem-inspect's; bad
// options exit 1 with the option named and nothing written.
#include "lsdem/ls/GrainCatalog.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/mesh/MeshValidation.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace lsdem;
using lsdem::test::runCommand;

namespace {

const std::string kBake = LSDEM_BAKE_EXE;
const std::string kGrains = LSDEM_GRAINS_EXE;
const std::string kInspect = LSDEM_INSPECT_EXE;

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

} // namespace

TEST(BatchTools, GrainsAreReproducibleValidMeshes)
{
    test::ScratchDir dir;
    const std::string options = " --count 3 --seed 4 --triangles 500 --max-degree 8 -q";
    for (const char* folder : {"a", "b"}) {
        const auto r = runCommand(kGrains + options + " --out-dir " + dir.file(folder));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    // --first 2 --count 1 makes the third grain alone: the same bytes.
    ASSERT_EQ(runCommand(kGrains + " --first 2 --count 1 --seed 4 --triangles 500 "
                                   "--max-degree 8 -q --out-dir " + dir.file("c"))
                  .exitCode,
              0);
    for (const char* name : {"grain_0000.stl", "grain_0001.stl", "grain_0002.stl"}) {
        const std::string a = dir.file(std::string("a/") + name);
        EXPECT_EQ(fileBytes(a), fileBytes(dir.file(std::string("b/") + name))) << name;
        TriangleMesh mesh = readMesh(a);
        const MeshValidationReport report = validateSolidMesh(mesh, a);
        EXPECT_EQ(report.reorientedTriangles + report.removedDegenerateTriangles, 0);
        EXPECT_FALSE(report.flippedToOutward);
    }
    EXPECT_EQ(fileBytes(dir.file("a/grain_0002.stl")), fileBytes(dir.file("c/grain_0002.stl")));
    // A chunk reaching past 9999 names its grains as a chunk below it does.
    ASSERT_EQ(runCommand(kGrains + " --first 9999 --count 2 --seed 4 --triangles 500 "
                                   "--max-degree 8 -q --out-dir " + dir.file("e"))
                  .exitCode,
              0);
    EXPECT_TRUE(std::filesystem::exists(dir.file("e/grain_9999.stl")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("e/grain_10000.stl")));
    const auto other = runCommand(kGrains + " --count 1 --seed 5 --triangles 500 --max-degree 8"
                                            " -q --out-dir " + dir.file("d"));
    ASSERT_EQ(other.exitCode, 0);
    EXPECT_NE(fileBytes(dir.file("a/grain_0000.stl")), fileBytes(dir.file("d/grain_0000.stl")));
}

TEST(BatchTools, BatchBakesTheGoodFilesListsTheCorruptOneAndExits4)
{
    test::ScratchDir dir;
    ASSERT_EQ(runCommand(kGrains + " --count 3 --triangles 320 --max-degree 6 --size 2 "
                                   "--size-spread 0.3 -q --out-dir " + dir.file("scans"))
                  .exitCode,
              0);
    {
        std::ofstream corrupt(dir.file("scans/grain_0001.stl"), std::ios::binary | std::ios::trunc);
        corrupt << "not a mesh at all";
    }
    const std::string bake = kBake + " " + dir.file("scans") + "/*.stl --out-dir " +
                             dir.file("assets") +
                             " --voxel-per-size 0.08 --nodes 150 --threads 2";
    const auto r = runCommand(bake);
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_TRUE(contains(r.output, "1 of 3 files failed")) << r.output;
    EXPECT_TRUE(contains(r.output, "grain_0001.stl")) << r.output;
    EXPECT_TRUE(contains(r.output, "[3/3]")) << r.output;  // the progress line
    EXPECT_FALSE(std::filesystem::exists(dir.file("assets/grain_0001.vdb")));

    const auto rows = readCatalog(dir.file("assets/catalog.csv"));
    ASSERT_EQ(rows.size(), 2u);
    for (const CatalogEntry& row : rows) {
        const std::string asset = dir.file("assets/" + row.asset);
        const auto inspect = runCommand(kInspect + " " + asset + " --json");
        ASSERT_EQ(inspect.exitCode, 0) << inspect.output;
        const nlohmann::json j = nlohmann::json::parse(inspect.output);
        // Both print doubles to round-trip: equal bit for bit.
        EXPECT_EQ(row.measures.volume, j["volume"].get<double>());
        EXPECT_EQ(row.measures.surfaceArea, j["node_area_sum"].get<double>());
        EXPECT_EQ(row.nodes, j["node_count"].get<long long>());
        EXPECT_EQ(row.vdp, j["voxel_size"].get<double>());
        EXPECT_EQ(row.sdp, j["node_spacing"]["mean"].get<double>());
        EXPECT_EQ(row.sourceSha256, j["source_sha256"].get<std::string>());
        EXPECT_EQ(row.source, j["source"].get<std::string>());
        // The level set's own measure agrees with the polyhedron's volume to the voxel's
        // resolution (a band of about one voxel over the surface).
        EXPECT_NEAR(j["level_set_volume"].get<double>() / row.measures.volume, 1.0,
                    row.vdp * row.measures.surfaceArea / row.measures.volume);
    }

    // Second run: nothing baked again, the corrupt file still reported.
    const auto again = runCommand(bake + " -q");
    EXPECT_EQ(again.exitCode, 4);
    const auto quiet = runCommand(kBake + " " + dir.file("scans/grain_0000.stl") + " " +
                                  dir.file("scans/grain_0002.stl") + " --out-dir " +
                                  dir.file("assets") + " --voxel-per-size 0.08 --nodes 150");
    EXPECT_EQ(quiet.exitCode, 0) << quiet.output;
    EXPECT_TRUE(contains(quiet.output, "baked 0, unchanged 2")) << quiet.output;
}

TEST(BatchTools, BadOptionsExit1AndWriteNothing)
{
    test::ScratchDir dir;
    struct Case
    {
        std::string args, expected;
    };
    const std::string out = " --out-dir " + dir.file("out");
    const std::vector<Case> bake = {
        {"a.stl b.stl --voxel 0.1 --nodes 100 -o x.vdb", "more than one input mesh"},
        {"a.stl --voxel-per-size 0.03 --nodes 100 -o x.vdb", "need --out-dir"},
        {"a.stl --voxel 0.1 --voxel-per-size 0.03 --nodes 100" + out, "exactly one of --voxel"},
        {"a.stl --voxel-per-size 3 --nodes 100" + out, "fraction in (0, 1)"},
        {"a.stl --voxel-per-size 0.03" + out, "say how to place surface nodes"},
        {"--sphere 1 --voxel 0.1 --nodes 100" + out, "not analytic shapes"},
        {"a.stl --voxel 0.1 --nodes 100 -o x.vdb" + out, "not both"},
        {"a.stl --voxel-per-size 0.03 --nodes 100 --threads -1" + out, "--threads"},
    };
    for (const Case& c : bake) {
        const auto r = runCommand(kBake + " " + c.args);
        EXPECT_EQ(r.exitCode, 1) << c.args << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, c.expected)) << c.args << "\n" << r.output;
    }
    const std::vector<Case> grains = {
        {"--elongation 1.2", "--elongation"}, {"--roughness nan", "--roughness"},
        {"--count 0", "--count"},             {"--format ply", "--format"},
        {"--max-degree 40 --triangles 500", "--triangles"},
        {"--size 1e40", "--size"},            {"--size 1e-50", "--size"},
        {"--first 9223372036854775807 --count 2", "--first"},
    };
    for (const Case& c : grains) {
        const auto r = runCommand(kGrains + " " + c.args + out);
        EXPECT_EQ(r.exitCode, 1) << c.args << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, c.expected)) << c.args << "\n" << r.output;
    }
    EXPECT_EQ(runCommand(kGrains + " --count 2").exitCode, 1);  // no --out-dir
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}
