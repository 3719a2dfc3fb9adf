// [asset_sets]: a catalogue written by the batch baker, or a glob of .vdb files, becomes one
// asset per row or file, named SET/ASSET; grains use them by name and get the right shape; the
// scene writer writes the set back so that the file reads to the same scene; bad sets are
// refused with the file, line and a fix.
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainCatalog.h"
#include "lsdem/ls/GrainGenerator.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace lsdem;

namespace {

/// A folder with two baked assets (a sphere "ball" and an ellipsoid "egg") and their
/// catalogue, as lsdem-bake --out-dir leaves it.
class AssetSetTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        std::filesystem::create_directories(dir.file("sand"));
        BakeOptions o;
        o.voxelSize = 0.25;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 100;
        std::vector<std::string> warnings;
        std::vector<CatalogEntry> rows;
        const std::pair<const char*, AnalyticShape> shapes[] = {
            {"egg", AnalyticShape::ellipsoid(2.0, 1.5, 1.0)}, {"ball", AnalyticShape::sphere(1.0)}};
        for (const auto& [name, shape] : shapes) {
            const GrainAsset asset = bakeAnalytic(shape, o, warnings);
            saveAsset(asset, dir.file("sand/" + std::string(name) + ".vdb"));
            rows.push_back(catalogEntry(asset, name, std::string(name) + ".vdb", "", 0.0));
        }
        writeCatalog(dir.file("sand/catalog.csv"), rows);  // egg first: the rows' order counts
    }

    /// A scene with the set @a setTable and grains of @a grainAssets.
    std::string scene(const std::string& setTable, const std::vector<std::string>& grainAssets)
    {
        std::string text = "[asset_sets.sand]\n" + setTable + "\n" +
                           "[materials.quartz]\ndensity = 2.65e-9\n\n"
                           "[[contacts]]\nmaterials = [\"quartz\", \"quartz\"]\n"
                           "normal_stiffness = 1e3\n";
        double x = 0.0;
        for (const std::string& a : grainAssets) {
            text += "\n[[grains]]\nasset = \"" + a + "\"\nmaterial = \"quartz\"\nposition = [" +
                    std::to_string(x) + ", 0, 0]\n";
            x += 5.0;
        }
        return text + "\n[simulation]\ngravity = [0, 0, 0]\nend_steps = 1\n";
    }

    std::string errorOf(const std::string& text)
    {
        try {
            parseScene(text, dir.file("scene.toml"));
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }

    test::ScratchDir dir;
};

} // namespace

TEST_F(AssetSetTest, CatalogueAssetsAreNamedBySetAndLoadTheirShapes)
{
    const Scene s = parseScene(scene("catalog = \"sand/catalog.csv\"", {"sand/ball", "sand/egg"}),
                               dir.file("scene.toml"));
    ASSERT_EQ(s.assets.size(), 2u);
    EXPECT_EQ(s.assets[0].name, "sand/egg");  // the catalogue's order
    EXPECT_EQ(s.assets[1].name, "sand/ball");
    EXPECT_EQ(s.assets[1].file, dir.file("sand/ball.vdb"));
    EXPECT_EQ(s.assets[1].set, "sand");
    ASSERT_EQ(s.assetSets.size(), 1u);
    EXPECT_EQ(s.assetSets[0].catalog, dir.file("sand/catalog.csv"));
    EXPECT_EQ(s.grains[0].asset, 1);
    EXPECT_EQ(s.grains[1].asset, 0);

    std::vector<std::string> warnings;
    const World w = buildWorld(s, warnings);
    // Each grain carries its own shape: the closed-form volumes of the sphere and ellipsoid.
    EXPECT_NEAR(w.grains[0].asset->mass.volume, 4.0 / 3.0 * kPi, 1e-12);
    EXPECT_NEAR(w.grains[1].asset->mass.volume, 4.0 / 3.0 * kPi * 3.0, 1e-12);
}

TEST_F(AssetSetTest, GlobTakesTheMatchingFilesInNameOrder)
{
    const Scene s = parseScene(scene("glob = \"sand/*.vdb\"", {"sand/egg"}),
                               dir.file("scene.toml"));
    ASSERT_EQ(s.assets.size(), 2u);
    EXPECT_EQ(s.assets[0].name, "sand/ball");
    EXPECT_EQ(s.assets[1].name, "sand/egg");
    EXPECT_EQ(s.assets[1].file, dir.file("sand/egg.vdb"));
    EXPECT_EQ(s.assetSets[0].glob, dir.file("sand/*.vdb"));
    EXPECT_EQ(s.grains[0].asset, 1);
}

TEST_F(AssetSetTest, GlobOfMeshesIsBakedAtLoadWithTheSetsOptions)
{
    std::filesystem::create_directories(dir.file("scans"));
    GrainShapeOptions g;
    g.triangles = 320;
    g.maxDegree = 6;
    g.size = 2.0;
    for (uint64_t i = 0; i < 2; ++i)
        writeGrainMesh(generateGrain(g, 1, i), dir.file("scans/g" + std::to_string(i) + ".obj"));
    const std::string table = "glob = \"scans/*.obj\"\nvoxel = 0.2\nnodes = 120";
    const Scene s = parseScene(scene(table, {"sand/g1", "sand/g0"}), dir.file("scene.toml"));
    ASSERT_EQ(s.assets.size(), 2u);
    EXPECT_EQ(s.assets[0].meshFile, dir.file("scans/g0.obj"));
    EXPECT_TRUE(s.assets[0].file.empty());
    EXPECT_EQ(s.assets[1].bake.voxelSize, 0.2);
    EXPECT_EQ(s.assets[1].bake.nodeCount, 120);
    EXPECT_TRUE(s.assetSets[0].meshes);

    std::vector<std::string> warnings;
    const World w = buildWorld(s, warnings);
    for (int i = 0; i < 2; ++i) {
        // Grain 0 uses g1, grain 1 uses g0: each baked from its own mesh.
        const std::string mesh = dir.file("scans/g" + std::to_string(1 - i) + ".obj");
        EXPECT_NEAR(w.grains[i].asset->mass.volume, computeMassProperties(readMesh(mesh)).volume,
                    1e-12);
        EXPECT_EQ(w.grains[i].asset->voxelSize, 0.2);
        EXPECT_FALSE(w.grains[i].asset->nodes.hasNormals());  // a simulation's copy
    }

    // The writer keeps the baking keys.
    const Scene back = parseScene(sceneToToml(s, dir.path().string()), dir.file("again.toml"));
    ASSERT_EQ(back.assets.size(), 2u);
    EXPECT_EQ(back.assets[1].meshFile, s.assets[1].meshFile);
    EXPECT_EQ(back.assets[1].bake.voxelSize, 0.2);
    EXPECT_EQ(back.assets[1].bake.nodePlacement, NodePlacement::Count);
    EXPECT_EQ(back.assets[1].bake.nodeCount, 120);

    // Bad: no baking keys for meshes, baking keys for baked assets, a mixed glob.
    EXPECT_NE(errorOf(scene("glob = \"scans/*.obj\"", {"sand/g0"})).find("missing key 'voxel'"),
              std::string::npos);
    EXPECT_NE(errorOf(scene("glob = \"sand/*.vdb\"\nvoxel = 0.1", {"sand/egg"}))
                  .find("voxel: has no effect on baked assets"),
              std::string::npos);
    std::filesystem::copy_file(dir.file("sand/egg.vdb"), dir.file("scans/egg.vdb"));
    EXPECT_NE(errorOf(scene("glob = \"scans/*\"\nvoxel = 0.2\nnodes = 100", {"sand/g0"}))
                  .find("both baked assets (.vdb) and other files"),
              std::string::npos);
}

TEST_F(AssetSetTest, WriterWritesTheSetBackAndItReadsToTheSameScene)
{
    for (const std::string table : {"catalog = \"sand/catalog.csv\"", "glob = \"sand/*.vdb\""}) {
        const std::string text =
            "[assets.single]\nfile = \"sand/ball.vdb\"\n\n" +
            scene(table, {"sand/ball", "single", "sand/egg"});
        const Scene a = parseScene(text, dir.file("scene.toml"));
        // Written from another folder: the set's path must still resolve.
        std::filesystem::create_directories(dir.file("copy"));
        writeSceneFile(a, dir.file("copy/scene.toml"));
        const Scene b = readSceneFile(dir.file("copy/scene.toml"));
        ASSERT_EQ(a.assets.size(), b.assets.size());
        for (size_t i = 0; i < a.assets.size(); ++i) {
            EXPECT_EQ(a.assets[i].name, b.assets[i].name);
            EXPECT_EQ(a.assets[i].file, b.assets[i].file);
            EXPECT_EQ(a.assets[i].set, b.assets[i].set);
        }
        ASSERT_EQ(b.assetSets.size(), 1u);
        EXPECT_EQ(a.assetSets[0].catalog, b.assetSets[0].catalog);
        EXPECT_EQ(a.assetSets[0].glob, b.assetSets[0].glob);
        ASSERT_EQ(a.grains.size(), b.grains.size());
        for (size_t i = 0; i < a.grains.size(); ++i)
            EXPECT_EQ(a.grains[i].asset, b.grains[i].asset);
        // One table for the set, not one per asset.
        EXPECT_EQ(sceneToToml(a, dir.path().string()).find("[assets.\"sand/"), std::string::npos);
    }
}

TEST_F(AssetSetTest, BadSetsAreRefusedWithThePlaceAndAFix)
{
    const std::string good = "catalog = \"sand/catalog.csv\"";
    struct Case
    {
        std::string text, expected;
    };
    writeTextFileAtomically(dir.file("sand/no-asset.csv"), "name,volume\nball,1\n");
    writeTextFileAtomically(dir.file("sand/nan.csv"),
                            "name,asset,volume\nball,ball.vdb,1\negg,egg.vdb,nan\n");
    writeTextFileAtomically(dir.file("sand/missing.csv"), "name,asset\nball,ball.vdb\nx,x.vdb\n");
    writeTextFileAtomically(dir.file("sand/empty.csv"), "name,asset\n");
    const std::vector<Case> cases = {
        {scene(good, {"sand/pebble"}), "no asset named 'sand/pebble'"},
        {scene(good, {"ball"}), "use one of 'sand/egg', 'sand/ball'"},
        {scene("catalog = \"sand/no-asset.csv\"", {"sand/ball"}),
         "no-asset.csv:1: the catalogue has no column 'asset'"},
        {scene("catalog = \"sand/nan.csv\"", {"sand/ball"}), "nan.csv:3: column 'volume': 'nan'"},
        {scene("catalog = \"sand/missing.csv\"", {"sand/ball"}),
         "asset 'x' of " + dir.file("sand/missing.csv") + ": file not found"},
        {scene("catalog = \"sand/empty.csv\"", {"sand/ball"}), "lists no assets"},
        {scene("catalog = \"sand/none.csv\"", {"sand/ball"}), "catalog: file not found"},
        {scene("catalog = \"/dev/zero\"", {"sand/ball"}), "catalog: file not found"},
        {scene(good + "\nglob = \"sand/*.vdb\"", {"sand/ball"}), "has both catalog and glob"},
        {scene("", {"sand/ball"}), "has neither catalog nor glob"},
        {scene("glob = \"sand/*.stl\"", {"sand/ball"}), "should match the mesh files"},
        {scene("glob = \"sand/*.stl\"", {"sand/ball"}), "matches no file"},
        {scene("glob = \"sand/x*.vdb\"", {"sand/ball"}), "bake the assets first"},
        {scene("glob = \"*/ball.vdb\"", {"sand/ball"}), "wildcard in a folder name"},
        {scene(good + "\ncolour = \"red\"", {"sand/ball"}), "unknown key 'colour'"},
    };
    for (const Case& c : cases) {
        const std::string message = errorOf(c.text);
        EXPECT_NE(message.find(c.expected), std::string::npos)
            << "got: " << message << "\nwanted: " << c.expected;
    }
    // The set's table is named in the scene: its line for keys of the table.
    EXPECT_NE(errorOf(scene("", {"sand/ball"})).find("scene.toml:1"), std::string::npos);
}

// The bundled example: the 16 generated grains of assets/meshes/sand, one grain each, baked at
// load; it reads, and reads back from the writer, to the same assets.
TEST(AssetSets, BundledSandSceneUsesEveryGrainOnce)
{
    const std::string path = std::string(LSDEM_SOURCE_DIR) + "/assets/scenes/sand.toml";
    const Scene s = readSceneFile(path);
    ASSERT_EQ(s.assets.size(), 16u);
    ASSERT_EQ(s.grains.size(), 16u);
    for (size_t i = 0; i < s.grains.size(); ++i) {
        EXPECT_EQ(s.grains[i].asset, static_cast<int>(i));
        EXPECT_TRUE(std::filesystem::is_regular_file(s.assets[i].meshFile));
    }
    test::ScratchDir dir;
    writeSceneFile(s, dir.file("sand.toml"));
    const Scene back = readSceneFile(dir.file("sand.toml"));
    ASSERT_EQ(back.assets.size(), 16u);
    for (size_t i = 0; i < s.assets.size(); ++i) {
        EXPECT_EQ(back.assets[i].name, s.assets[i].name);
        EXPECT_EQ(back.assets[i].meshFile, s.assets[i].meshFile);
        EXPECT_EQ(back.assets[i].bake.voxelSize, s.assets[i].bake.voxelSize);
    }
}
