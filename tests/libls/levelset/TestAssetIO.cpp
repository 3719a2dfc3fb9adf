// Asset files: exact round trip of every field, sharing, and clean failures on bad files.
#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/core/Sha256.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cstdint>
#include <fstream>
#include <limits>

using namespace lsdem;

namespace {

GrainAsset smallAsset()
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = 0.25;
    o.optionsText = "--ellipsoid 1.5 1 0.7 --voxel 0.1 --node-spacing 0.25";
    std::vector<std::string> warnings;
    return bakeAnalytic(AnalyticShape::ellipsoid(1.5, 1.0, 0.7), o, warnings);
}

/// Every field of @a a and @a b bit for bit (the nodes' normals only if @a withNormals).
void expectSameAsset(const GrainAsset& a, const GrainAsset& b, bool withNormals = true)
{
    EXPECT_EQ(a.voxelSize, b.voxelSize);
    EXPECT_EQ(a.exteriorBandVoxels, b.exteriorBandVoxels);
    EXPECT_EQ(a.levelSet->origin, b.levelSet->origin);
    EXPECT_EQ(a.mass.volume, b.mass.volume);
    EXPECT_EQ(a.mass.centroid, b.mass.centroid);
    EXPECT_EQ(a.mass.inertia, b.mass.inertia);
    EXPECT_EQ(a.inputFrame.rotation, b.inputFrame.rotation);
    EXPECT_EQ(a.inputFrame.centroid, b.inputFrame.centroid);
    EXPECT_EQ(a.inputFrame.moments, b.inputFrame.moments);
    EXPECT_EQ(a.areaRule, b.areaRule);
    EXPECT_EQ(a.spacing.mean, b.spacing.mean);
    EXPECT_EQ(a.spacing.min, b.spacing.min);
    EXPECT_EQ(a.spacing.max, b.spacing.max);
    EXPECT_EQ(a.boundingRadius, b.boundingRadius);
    EXPECT_EQ(a.provenance.source, b.provenance.source);
    EXPECT_EQ(a.provenance.sourceSha256, b.provenance.sourceSha256);
    EXPECT_EQ(a.provenance.options, b.provenance.options);
    EXPECT_EQ(a.provenance.lsdemVersion, b.provenance.lsdemVersion);
    EXPECT_EQ(a.provenance.nodeLayout, "remesh, projected");  // an ellipsoid's
    EXPECT_EQ(a.provenance.nodeLayout, b.provenance.nodeLayout);
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (size_t i = 0; i < a.nodes.size(); ++i) {
        EXPECT_EQ(a.nodes.positions[i], b.nodes.positions[i]) << i;
        if (withNormals) {
            EXPECT_EQ(a.nodes.normals[i], b.nodes.normals[i]) << i;
        }
        EXPECT_EQ(a.nodes.areas[i], b.nodes.areas[i]) << i;
    }
    // Every voxel: same active state and bit-identical value.
    const auto& ga = *a.levelSet->grid;
    const auto& gb = *b.levelSet->grid;
    EXPECT_EQ(ga.activeVoxelCount(), gb.activeVoxelCount());
    EXPECT_EQ(ga.background(), gb.background());
    const openvdb::FloatGrid::Ptr standard = toFloatGrid(ga);
    for (auto it = standard->cbeginValueOn(); it; ++it) {
        ASSERT_TRUE(gb.isValueOn(it.getCoord()));
        ASSERT_EQ(*it, gb.value(it.getCoord()));
    }
}

} // namespace

TEST(AssetIO, RoundTripPreservesEveryField)
{
    test::ScratchDir dir;
    const GrainAsset asset = smallAsset();
    saveAsset(asset, dir.file("grain.vdb"));
    EXPECT_EQ(dir.entryCount(), 1u);  // no temporary left behind
    const auto loaded = loadAsset(dir.file("grain.vdb"));
    expectSameAsset(asset, *loaded);
}

// A simulation loads assets without the nodes' normals (no contact law reads them): all else
// is the same to the bit, what a load derives too, and such a copy is not saved as if whole.
TEST(AssetIO, LoadingWithoutNormalsKeepsEverythingElse)
{
    test::ScratchDir dir;
    const GrainAsset asset = smallAsset();
    saveAsset(asset, dir.file("grain.vdb"));
    const auto whole = loadAsset(dir.file("grain.vdb"));
    const auto lean = loadAsset(dir.file("grain.vdb"), NodeNormals::Skip);
    EXPECT_TRUE(whole->nodes.hasNormals());
    EXPECT_FALSE(lean->nodes.hasNormals());
    EXPECT_EQ(lean->nodes.normals.capacity(), 0u);
    expectSameAsset(asset, *lean, /*withNormals=*/false);
    EXPECT_EQ(lean->insideBoxMin, whole->insideBoxMin);
    EXPECT_EQ(lean->insideBoxMax, whole->insideBoxMax);
    EXPECT_EQ(lean->levelSetSlope, whole->levelSetSlope);
    ASSERT_EQ(lean->nodeBlocks.blocks.size(), whole->nodeBlocks.blocks.size());
    for (size_t k = 0; k < lean->nodeBlocks.blocks.size(); ++k) {
        EXPECT_EQ(lean->nodeBlocks.blocks[k].begin, whole->nodeBlocks.blocks[k].begin);
        EXPECT_EQ(lean->nodeBlocks.blocks[k].end, whole->nodeBlocks.blocks[k].end);
        EXPECT_EQ(lean->nodeBlocks.blocks[k].center, whole->nodeBlocks.blocks[k].center);
        EXPECT_EQ(lean->nodeBlocks.blocks[k].radius, whole->nodeBlocks.blocks[k].radius);
    }
    try {
        saveAsset(*lean, dir.file("copy.vdb"));
        ADD_FAILURE() << "an asset without normals was saved";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("copy.vdb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no normals"), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.entryCount(), 1u);  // nothing half-written
}

// The nodes grid is a standard OpenVDB points grid: a viewer places each node at its voxel
// plus the offset P, through the grid's transform. That must be the node's position.
TEST(AssetIO, ViewersSeeTheNodesWhereTheyAre)
{
    test::ScratchDir dir;
    const GrainAsset asset = smallAsset();
    saveAsset(asset, dir.file("grain.vdb"));
    openvdb::io::File file(dir.file("grain.vdb"));
    file.open();
    const auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("nodes"));
    file.close();
    ASSERT_TRUE(grid);
    const openvdb::math::Transform& xform = grid->transform();
    size_t seen = 0;
    for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
        const openvdb::points::AttributeHandle<openvdb::Vec3f> offset(
            leaf->constAttributeArray("P"));
        const openvdb::points::AttributeHandle<int32_t> id(leaf->constAttributeArray("node_id"));
        for (auto index = leaf->beginIndexOn(); index; ++index) {
            const openvdb::Vec3d voxel = index.getCoord().asVec3d() + offset.get(*index);
            const openvdb::Vec3d world = xform.indexToWorld(voxel);
            const Vec3& node = asset.nodes.positions[size_t(id.get(*index))];
            for (int k = 0; k < 3; ++k)  // P is a float offset within a voxel
                EXPECT_NEAR(world[k], node[k], 1e-6 * xform.voxelSize()[0]);
            ++seen;
        }
    }
    EXPECT_EQ(seen, asset.nodes.size());
}

TEST(AssetIO, LibraryLoadsEachFileOnceAndShares)
{
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("grain.vdb"));
    AssetLibrary library;
    const auto first = library.get(dir.file("grain.vdb"));
    const auto second = library.get(dir.path().string() + "/./grain.vdb");
    EXPECT_EQ(first.get(), second.get());
    EXPECT_EQ(library.size(), 1u);
}

TEST(AssetIO, BadFilesFailCleanlyNamingTheFile)
{
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("good.vdb"));
    std::string bytes;
    {
        std::ifstream in(dir.file("good.vdb"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ASSERT_GT(bytes.size(), 1000u);
    // Truncated at several places, garbage, empty, a folder, a missing file.
    for (double fraction : {0.0, 0.01, 0.3, 0.7, 0.99}) {
        const std::string path = dir.file("cut.vdb");
        std::ofstream(path, std::ios::binary) << bytes.substr(0, size_t(fraction * bytes.size()));
        try {
            loadAsset(path);
            ADD_FAILURE() << "a file cut at " << fraction << " loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    std::ofstream(dir.file("garbage.vdb")) << "this is not an OpenVDB file at all";
    EXPECT_THROW(loadAsset(dir.file("garbage.vdb")), Error);
    EXPECT_THROW(loadAsset(dir.file("missing.vdb")), Error);
    EXPECT_THROW(loadAsset(dir.path().string()), Error);
}

// Found by fuzzing (fuzz/corpus/asset/regression-*): OpenVDB allocates whatever a length field
// says, so a damaged length made loadAsset take gigabytes before failing. The SHA-256 seal
// written by saveAsset is checked first, by a parser that bounds each length by the file size.
TEST(AssetIO, DamagedLengthFieldIsRefusedBeforeOpenVdbReadsIt)
{
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("good.vdb"));
    std::string bytes;
    {
        std::ifstream in(dir.file("good.vdb"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto write = [&](const std::string& name, const std::string& content) {
        std::ofstream(dir.file(name), std::ios::binary) << content;
        return dir.file(name);
    };
    const auto expectRefused = [](const std::string& path, const std::string& message) {
        try {
            loadAsset(path);
            ADD_FAILURE() << path << " loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path);
            EXPECT_NE(e.problem().find(message), std::string::npos) << e.what();
            EXPECT_FALSE(e.fix().empty());
        }
    };
    // The length of the grid name "phi" (after the seal): 4 GiB - 16.
    const size_t phi = bytes.find(std::string("\x03\0\0\0phi", 7));
    ASSERT_NE(phi, std::string::npos);
    std::string longName = bytes;
    longName.replace(phi, 4, "\xf0\xff\xff\xff");
    expectRefused(write("long-name.vdb", longName), "damaged");
    // The length of the seal's own key, within the metadata our parser reads.
    const size_t key = bytes.find("lsdem_sha256");
    ASSERT_NE(key, std::string::npos);
    std::string longKey = bytes;
    longKey.replace(key - 4, 4, "\xf0\xff\xff\xff");
    expectRefused(write("long-key.vdb", longKey), "the file ends inside the file metadata");
    // One flipped bit far inside the grids.
    std::string flipped = bytes;
    flipped[bytes.size() / 2] = static_cast<char>(flipped[bytes.size() / 2] ^ 0x10);
    expectRefused(write("flipped.vdb", flipped), "damaged");
}

namespace {

/// @a bytes with its seal recomputed, as someone editing a file on purpose would do.
std::string resealed(std::string bytes)
{
    const std::string key = "lsdem_sha256";
    const size_t digits = bytes.find(key) + key.size() + 4 + 6 + 4;  // "string", its size
    bytes.replace(digits, 64, std::string(64, '0'));
    bytes.replace(digits, 64, sha256Hex(bytes));
    return bytes;
}

} // namespace

// Found by fuzzing (fuzz/corpus/asset/regression-sealed-*): libFuzzer forges the seal (it sees
// both sides of the comparison), and the next damaged length OpenVDB trusted was in the grid
// descriptors. The headers of every grid are checked after the seal, the same way.
TEST(AssetIO, HandMadeGridHeadersAreRefusedEvenWhenSealed)
{
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("good.vdb"));
    std::string bytes;
    {
        std::ifstream in(dir.file("good.vdb"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    EXPECT_EQ(resealed(bytes), bytes);  // the helper computes the seal saveAsset wrote
    struct Case
    {
        const char* what;
        std::string field;        ///< bytes to find
        size_t offset;            ///< where in them the length starts
        std::string replacement;  ///< 4 bytes
        const char* message;
    };
    const std::string huge("\xf0\xff\xff\x7f", 4);
    const Case cases[] = {
        {"grid name", std::string("\x05\0\0\0nodes", 9), 0, huge, "grid descriptor"},
        {"grid count", std::string("\x02\0\0\0\x03\0\0\0phi", 11), 0, huge, "grid count"},
        {"metadata string", std::string("\x06\0\0\0source\x06\0\0\0string", 20), 20, huge,
         "grid metadata"},
        {"leaf index count", std::string("__delayedload", 13), 17, huge, "leaf index"},
    };
    for (const Case& c : cases) {
        const size_t at = bytes.find(c.field);
        ASSERT_NE(at, std::string::npos) << c.what;
        std::string edited = bytes;
        edited.replace(at + c.offset, 4, c.replacement);
        const std::string path = dir.file("edited.vdb");
        std::ofstream(path, std::ios::binary) << resealed(edited);
        try {
            loadAsset(path);
            ADD_FAILURE() << c.what << ": loaded";
        } catch (const Error& e) {
            EXPECT_NE(e.problem().find("not a readable lsdem asset"), std::string::npos)
                << c.what << ": " << e.what();
            EXPECT_NE(e.problem().find(c.message), std::string::npos) << c.what << ": " << e.what();
        }
    }
}

// Found by review while writing the asset fuzzer: values OpenVDB reads fine but lsdem trusted.
// A node_count of 1e12 made loadAsset allocate for 1e12 nodes (std::bad_alloc escaped), a NaN
// voxel size passed the transform check (NaN compares false).
TEST(AssetIO, HandMadeMetadataValuesAreRefusedEvenWhenSealed)
{
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("good.vdb"));
    std::string bytes;
    {
        std::ifstream in(dir.file("good.vdb"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto valueOf = [&](const std::string& key, const std::string& type) {
        const std::string entry = key + char(type.size()) + std::string(3, '\0') + type;
        const size_t at = bytes.find(entry);
        EXPECT_NE(at, std::string::npos) << key;
        return at + entry.size() + 4;  // after the value's size
    };
    const auto expectRefused = [&](std::string edited, const std::string& message) {
        const std::string path = dir.file("edited.vdb");
        std::ofstream(path, std::ios::binary) << resealed(edited);
        try {
            loadAsset(path);
            ADD_FAILURE() << "loaded: " << message;
        } catch (const Error& e) {
            EXPECT_NE(e.problem().find(message), std::string::npos) << e.what();
        }
    };
    std::string manyNodes = bytes;
    const int64_t trillion = 1000000000000;
    manyNodes.replace(valueOf("node_count", "int64"), 8,
                      std::string(reinterpret_cast<const char*>(&trillion), 8));
    expectRefused(manyNodes, "metadata says 1000000000000");
    std::string nanVoxel = bytes;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    nanVoxel.replace(valueOf("voxel_size", "double"), 8,
                     std::string(reinterpret_cast<const char*>(&nan), 8));
    expectRefused(nanVoxel, "not a finite length");
}

TEST(AssetIO, UnsealedFileIsRefused)
{
    // The grids of an asset written by OpenVDB alone, as lsdem before format 2 did.
    test::ScratchDir dir;
    saveAsset(smallAsset(), dir.file("sealed.vdb"));
    openvdb::io::File sealed(dir.file("sealed.vdb"));
    sealed.open();
    openvdb::io::File(dir.file("unsealed.vdb")).write(*sealed.getGrids());
    sealed.close();
    try {
        loadAsset(dir.file("unsealed.vdb"));
        FAIL() << "an unsealed asset loaded";
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("no checksum"), std::string::npos) << e.what();
        EXPECT_NE(e.fix().find("lsdem-bake"), std::string::npos) << e.what();
    }
}

TEST(AssetIO, ForeignLevelSetIsNotMistakenForAnAsset)
{
    test::ScratchDir dir;
    initializeOpenVdb();
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, {0, 0, 0}, 0.1f);
    openvdb::io::File(dir.file("foreign.vdb")).write({sphere});
    try {
        loadAsset(dir.file("foreign.vdb"));
        FAIL() << "a foreign level set loaded as an asset";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("foreign.vdb"), std::string::npos);
    }
}

TEST(AssetIO, UnwritableFolderFails)
{
    EXPECT_THROW(saveAsset(smallAsset(), "/nonexistent-folder-lsdem/grain.vdb"), Error);
}

// An asset written before the node layout was recorded (the fuzz corpus keeps one, baked
// 2026-11-26) loads, its layout unknown.
TEST(AssetIO, AnAssetFromBeforeTheNodeLayoutWasRecordedLoads)
{
    const auto asset =
        loadAsset(std::string(LSDEM_SOURCE_DIR) + "/fuzz/corpus/asset/sphere-r1-voxel0.2.vdb");
    EXPECT_GT(asset->nodes.size(), 0u);
    EXPECT_EQ(asset->provenance.nodeLayout, "");
}
