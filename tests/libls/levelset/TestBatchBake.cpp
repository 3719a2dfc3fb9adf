// Batch baking: generated grains and one corrupt file baked on two threads; the good files are
// baked and catalogued with their assets' own values, the corrupt one listed; voxel and node
// spacing per size follow each grain's size; an unchanged second run bakes nothing; the thread
// count changes nothing but the timings.
#include "lsdem/ls/BatchBake.h"

#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainGenerator.h"
#include "lsdem/mesh/MeshIO.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace lsdem;

namespace {

/// Three small generated grains of different sizes and a corrupt STL among them.
/// Small generated grains (a few hundred triangles), quick to bake.
GrainShapeOptions smallGrains()
{
    GrainShapeOptions g;
    g.triangles = 320;
    g.maxDegree = 6;
    g.sizeSpread = 0.4;
    return g;
}

std::vector<std::string> makeInputs(const test::ScratchDir& dir)
{
    const GrainShapeOptions g = smallGrains();
    std::vector<std::string> files;
    for (uint64_t i = 0; i < 3; ++i) {
        files.push_back(dir.file("grain_" + std::to_string(i) + ".stl"));
        writeGrainMesh(generateGrain(g, 1, i), files.back());
    }
    files.insert(files.begin() + 1, dir.file("broken.stl"));
    writeTextFileAtomically(files[1], "solid broken\n  facet normal 0 0 1\n    outer loop\n");
    return files;
}

BatchBakeOptions smallBake(const std::string& outDir, int threads)
{
    BatchBakeOptions o;
    o.voxelPerSize = 0.08;
    o.nodeSpacingPerSize = 0.15;
    o.bake.nodePlacement = NodePlacement::Spacing;
    o.outDir = outDir;
    o.threads = threads;
    return o;
}

/// Three good grain files baked into @a out, then grain_1's asset truncated (a damaged file
/// the next run finds); returns the files.
std::vector<std::string> bakeThreeAndDamageTheSecond(const test::ScratchDir& dir,
                                                     const std::string& out)
{
    std::vector<std::string> files = makeInputs(dir);
    files.erase(files.begin() + 1);  // no broken file here
    bakeBatch(files, smallBake(out, 1));
    const std::string asset = out + "/grain_1.vdb";
    writeTextFileAtomically(asset, test::readFile(asset).substr(0, 2000));
    return files;
}

/// The names of the rows of the catalogue at @a path, in its order.
std::vector<std::string> catalogNames(const std::string& path)
{
    std::vector<std::string> names;
    for (const CatalogEntry& e : readCatalog(path)) names.push_back(e.name);
    return names;
}

/// smallBake with a memory budget no bake meets (the budget is not among the options a
/// catalogue row records, so it does not make a file out of date).
BatchBakeOptions starvedBake(const std::string& outDir)
{
    BatchBakeOptions o = smallBake(outDir, 1);
    o.bake.memoryBudgetBytes = 1024.0;
    return o;
}

} // namespace

TEST(BatchBake, BakesTheGoodFilesAndListsTheBadOne)
{
    test::ScratchDir dir;
    const std::vector<std::string> files = makeInputs(dir);
    const std::string out = dir.file("assets");
    size_t calls = 0;
    const BatchBakeReport r = bakeBatch(files, smallBake(out, 2),
                                        [&](size_t done, size_t total, const std::string&) {
                                            EXPECT_EQ(done, ++calls);
                                            EXPECT_EQ(total, 4u);
                                        });
    EXPECT_EQ(calls, 4u);
    EXPECT_EQ(r.baked, 3);
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].source, files[1]);
    EXPECT_NE(r.failures[0].message.find("broken.stl"), std::string::npos)
        << r.failures[0].message;
    EXPECT_FALSE(std::filesystem::exists(out + "/broken.vdb"));

    // The catalogue on disk: sorted by name, each row its asset's own values.
    const std::vector<CatalogEntry> rows = readCatalog(r.catalogPath);
    ASSERT_EQ(rows.size(), 3u);
    for (size_t i = 0; i < rows.size(); ++i) {
        const CatalogEntry& row = rows[i];
        EXPECT_EQ(row.name, "grain_" + std::to_string(i));
        EXPECT_EQ(row.source, dir.file(row.name + ".stl"));
        const auto asset = loadAsset(out + "/" + row.asset);
        EXPECT_EQ(row.measures.volume, asset->mass.volume);
        EXPECT_EQ(row.measures.surfaceArea, asset->nodes.totalArea());
        EXPECT_EQ(row.nodes, static_cast<long long>(asset->nodes.size()));
        EXPECT_EQ(row.vdp, asset->voxelSize);
        EXPECT_EQ(row.sdp, asset->spacing.mean);
        EXPECT_EQ(row.sourceSha256, asset->provenance.sourceSha256);
        EXPECT_GT(row.bakeSeconds, 0.0);
        // Per size: the voxel is 0.08 of this grain's equivalent diameter, (6V/π)^(1/3).
        const double d = std::cbrt(6.0 * asset->mass.volume / kPi);
        EXPECT_NEAR(row.measures.equivalentDiameter, d, 1e-12 * d);
        EXPECT_NEAR(asset->voxelSize, 0.08 * d, 1e-6 * d);  // volume of the float32 STL
        EXPECT_NEAR(asset->spacing.mean / (0.15 * d), 1.0, 0.25);  // remeshing to a target
    }
    EXPECT_NE(rows[0].measures.equivalentDiameter, rows[1].measures.equivalentDiameter);
}

TEST(BatchBake, UnchangedFilesAreNotBakedAgain)
{
    test::ScratchDir dir;
    std::vector<std::string> files = makeInputs(dir);
    files.erase(files.begin() + 1);  // no broken file here
    const std::string out = dir.file("assets");
    EXPECT_EQ(bakeBatch(files, smallBake(out, 2)).baked, 3);
    const auto firstRows = readCatalog(out + "/catalog.csv");

    const BatchBakeReport again = bakeBatch(files, smallBake(out, 2));
    EXPECT_EQ(again.baked, 0);
    EXPECT_EQ(again.unchanged, 3);
    const auto rows = readCatalog(out + "/catalog.csv");
    ASSERT_EQ(rows.size(), 3u);
    for (size_t i = 0; i < rows.size(); ++i)
        EXPECT_EQ(rows[i].bakeSeconds, firstRows[i].bakeSeconds);  // the old rows, kept

    // A changed source is baked again; so is everything when the options change.
    GrainShapeOptions g;
    g.triangles = 320;
    g.maxDegree = 6;
    writeGrainMesh(generateGrain(g, 99, 0), files[0]);
    const BatchBakeReport changed = bakeBatch(files, smallBake(out, 2));
    EXPECT_EQ(changed.baked, 1);
    EXPECT_EQ(changed.unchanged, 2);
    BatchBakeOptions finer = smallBake(out, 2);
    finer.voxelPerSize = 0.07;
    EXPECT_EQ(bakeBatch(files, finer).baked, 3);

    // Baking part of the set keeps the other rows.
    const BatchBakeReport part = bakeBatch({files[1]}, finer);
    EXPECT_EQ(part.unchanged, 1);
    EXPECT_EQ(readCatalog(out + "/catalog.csv").size(), 3u);
}

TEST(BatchBake, ThreadCountChangesOnlyTheTimings)
{
    test::ScratchDir dir;
    std::vector<std::string> files = makeInputs(dir);
    const BatchBakeReport one = bakeBatch(files, smallBake(dir.file("one"), 1));
    const BatchBakeReport two = bakeBatch(files, smallBake(dir.file("two"), 2));
    ASSERT_EQ(one.entries.size(), two.entries.size());
    for (size_t i = 0; i < one.entries.size(); ++i) {
        const CatalogEntry &a = one.entries[i], &b = two.entries[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.measures.volume, b.measures.volume);
        EXPECT_EQ(a.measures.surfaceArea, b.measures.surfaceArea);
        EXPECT_EQ(a.measures.lengthLong, b.measures.lengthLong);
        EXPECT_EQ(a.nodes, b.nodes);
        EXPECT_EQ(a.sdp, b.sdp);
    }
    EXPECT_EQ(one.failures.size(), 1u);
    EXPECT_EQ(two.failures.size(), 1u);
}

TEST(BatchBake, TwoFilesWithOneNameAreRefusedBeforeAnyWork)
{
    test::ScratchDir dir;
    std::filesystem::create_directories(dir.file("a"));
    std::filesystem::create_directories(dir.file("b"));
    try {
        bakeBatch({dir.file("a/g.stl"), dir.file("b/g.stl")}, smallBake(dir.file("out"), 1));
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("same name 'g'"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// Found by review: a catalogue that could not be read (a nan cell) was replaced by one holding
// only the new rows. The batch now stops before any work and leaves it as it was.
TEST(BatchBake, UnreadableCatalogueIsKeptAndNothingIsBaked)
{
    test::ScratchDir dir;
    std::vector<std::string> files = makeInputs(dir);
    files.erase(files.begin() + 1);  // no broken file here
    const std::string out = dir.file("assets");
    bakeBatch({files[0], files[1]}, smallBake(out, 1));
    std::string catalogue = test::readFile(out + "/catalog.csv");
    // A row of the user's under the header, its volume not a number.
    const std::string handMade = "hand_made,hand_made.vdb,,,,nan" + std::string(12, ',');
    catalogue.insert(catalogue.find('\n') + 1, handMade + "\n");
    writeTextFileAtomically(out + "/catalog.csv", catalogue);
    try {
        bakeBatch(files, smallBake(out, 1));
        ADD_FAILURE() << "baked over an unreadable catalogue";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), out + "/catalog.csv:2");
        EXPECT_NE(e.problem().find("'nan'"), std::string::npos) << e.what();
        EXPECT_NE(e.fix().find("move the catalogue away"), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::readFile(out + "/catalog.csv"), catalogue);
    EXPECT_FALSE(std::filesystem::exists(out + "/grain_2.vdb"));
}

// Found by review: a file that failed to bake again lost its catalogue row, although its
// earlier asset was still there and valid.
TEST(BatchBake, FailedRebakeKeepsTheEarlierAssetAndRow)
{
    test::ScratchDir dir;
    std::vector<std::string> files = makeInputs(dir);
    files.erase(files.begin() + 1);  // no broken file here
    const std::string out = dir.file("assets");
    bakeBatch(files, smallBake(out, 1));
    const std::vector<CatalogEntry> before = readCatalog(out + "/catalog.csv");
    const std::string asset = test::readFile(out + "/grain_0.vdb");

    writeTextFileAtomically(files[0], "solid broken\n  facet normal 0 0 1\n");
    const BatchBakeReport r = bakeBatch(files, smallBake(out, 1));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].source, files[0]);
    const std::vector<CatalogEntry> after = readCatalog(out + "/catalog.csv");
    ASSERT_EQ(after.size(), before.size());
    EXPECT_EQ(after[0].name, "grain_0");
    EXPECT_EQ(after[0].sourceSha256, before[0].sourceSha256);
    EXPECT_EQ(test::readFile(out + "/grain_0.vdb"), asset);
}

// Found by review: with --voxel-per-size the batch validated (and repaired) each mesh itself to
// measure it, dropped the report, and bakeMesh then found nothing to report.
TEST(BatchBake, RepairsAreReportedAlikeWithVoxelPerSize)
{
    test::ScratchDir dir;
    TriangleMesh cube = AnalyticShape::box(1, 1, 1).surfaceMesh(0.25);
    for (auto& t : cube.triangles) std::swap(t[1], t[2]);
    writeMesh(cube, dir.file("inside_out.obj"));
    BatchBakeOptions absolute = smallBake(dir.file("absolute"), 1);
    absolute.voxelPerSize = absolute.nodeSpacingPerSize = 0.0;
    absolute.bake.voxelSize = 0.1;
    absolute.bake.nodeSpacing = 0.2;
    const BatchBakeReport a = bakeBatch({dir.file("inside_out.obj")}, absolute);
    const BatchBakeReport p =
        bakeBatch({dir.file("inside_out.obj")}, smallBake(dir.file("per-size"), 1));
    ASSERT_EQ(a.warnings.size(), 1u);
    EXPECT_NE(a.warnings[0].find("inside-out"), std::string::npos) << a.warnings[0];
    EXPECT_EQ(p.warnings, a.warnings);
}

// Found by review: a re-run counted a truncated asset as unchanged (its file was there), so the
// catalogue kept pointing at a file no simulation could load.
TEST(BatchBake, DamagedAssetIsBakedAgain)
{
    test::ScratchDir dir;
    const std::string out = dir.file("assets");
    const std::vector<std::string> files = bakeThreeAndDamageTheSecond(dir, out);
    const std::string asset = out + "/grain_1.vdb";

    const BatchBakeReport r = bakeBatch(files, smallBake(out, 1));
    EXPECT_EQ(r.baked, 1);
    EXPECT_EQ(r.unchanged, 2);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find(asset + ": the file is damaged"), std::string::npos)
        << r.warnings[0];
    EXPECT_NE(r.warnings[0].find("baking it again"), std::string::npos) << r.warnings[0];
    EXPECT_NO_THROW(loadAsset(asset));
}
// A damaged asset whose new bake fails too loses its row: the catalogue would otherwise list
// an asset that no simulation can load. (Here the bake fails on a tiny memory budget, which
// is not part of the options a row records, so the file counts as up to date but damaged.)
TEST(BatchBake, DamagedAssetThatFailsToBakeAgainLosesItsRow)
{
    test::ScratchDir dir;
    const std::string out = dir.file("assets");
    const std::vector<std::string> files = bakeThreeAndDamageTheSecond(dir, out);

    const BatchBakeReport r = bakeBatch(files, starvedBake(out));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].source, files[1]);
    EXPECT_EQ(r.unchanged, 2);
    EXPECT_EQ(catalogNames(r.catalogPath), (std::vector<std::string>{"grain_0", "grain_2"}));
}

// The same when the mesh was edited too (so the earlier row is not up to date and its asset
// is not checked before the bake): a failed bake still drops the row of a damaged asset.
TEST(BatchBake, DamagedAssetOfAnEditedMeshThatFailsToBakeLosesItsRow)
{
    test::ScratchDir dir;
    const std::string out = dir.file("assets");
    const std::vector<std::string> files = bakeThreeAndDamageTheSecond(dir, out);
    writeGrainMesh(generateGrain(smallGrains(), 7, 1), files[1]);  // edited: another grain

    const BatchBakeReport r = bakeBatch(files, starvedBake(out));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(catalogNames(r.catalogPath), (std::vector<std::string>{"grain_0", "grain_2"}));
}
