// Inspection: the report's figures against closed forms, slices and isosurfaces.
#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/Inspection.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/ls/SlicePlot.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <fstream>

using namespace lsdem;
using lsdem::kPi;

namespace {

InspectionTarget bakedSphere(const test::ScratchDir& dir, double radius, double vox)
{
    BakeOptions o;
    o.voxelSize = vox;
    o.nodeSpacing = 2.5 * vox;
    std::vector<std::string> warnings;
    saveAsset(bakeAnalytic(AnalyticShape::sphere(radius), o, warnings), dir.file("s.vdb"));
    return openForInspection(dir.file("s.vdb"));
}

} // namespace

TEST(Inspection, SphereReportMatchesClosedForms)
{
    test::ScratchDir dir;
    const double radius = 2.0, vox = 0.1;
    const InspectionTarget t = bakedSphere(dir, radius, vox);
    ASSERT_TRUE(t.asset);
    const InspectionReport r = inspect(t);
    EXPECT_EQ(r.voxelSize, vox);
    // The filled interior makes the active voxels about the ball plus a shell as wide as the
    // exterior band.
    const double band = BakeOptions().exteriorBandVoxels * vox;
    const double ballVoxels = 4.0 / 3.0 * kPi * std::pow(radius + band, 3) / (vox * vox * vox);
    EXPECT_NEAR(double(r.activeVoxels), ballVoxels, 0.05 * ballVoxels);
    EXPECT_NEAR(r.levelSetArea, 4 * kPi * radius * radius, 0.5 * vox / radius * 4 * kPi * radius * radius);
    EXPECT_NEAR(r.nodeAreaSum, 4 * kPi * radius * radius, 0.02 * 4 * kPi * radius * radius);
    EXPECT_LT(r.maxAbsPhiAtNodesVoxels, 3 * vox / (8 * radius) + 1e-4);
    // The exact distance has |∇φ| = 1 everywhere in the band; central differences err by
    // O(vox/R) only.
    EXPECT_GT(r.bandVoxels, 0);
    EXPECT_EQ(r.bandGradientOffShare, 0.0);
    EXPECT_GE(r.worldMin.x(), -radius - 4 * vox);
    EXPECT_LE(r.worldMax.x(), radius + 4 * vox);
}

TEST(Inspection, IsosurfaceIsClosedOutwardAndEnclosesTheVolume)
{
    test::ScratchDir dir;
    const double radius = 2.0, vox = 0.1;
    const InspectionTarget t = bakedSphere(dir, radius, vox);
    const TriangleMesh mesh = zeroIsosurface(*t.levelSet);
    const double volume = computeMassProperties(mesh).volume;  // positive iff outward
    const double exact = 4.0 / 3.0 * kPi * radius * radius * radius;
    EXPECT_NEAR(volume, exact, 0.02 * exact);

    // Meshed at 4 voxels: about 16 times fewer triangles, still closed, outward and enclosing
    // the sphere to second order in the coarser voxel (0.4/2 = 20 % of R: a few per cent).
    const TriangleMesh coarse = zeroIsosurface(*t.levelSet, 4 * vox);
    EXPECT_LT(coarse.triangles.size() * 8, mesh.triangles.size());
    EXPECT_NEAR(computeMassProperties(coarse).volume, exact, 0.06 * exact);
}

TEST(Inspection, SliceWritesAPngAndRefusesPlanesOffTheGrid)
{
    test::ScratchDir dir;
    const InspectionTarget t = bakedSphere(dir, 1.0, 0.1);
    writeSlicePng(t, parseSliceSpec("z=0.25"), dir.file("slice.png"));
    std::ifstream in(dir.file("slice.png"), std::ios::binary);
    char signature[8];
    in.read(signature, 8);
    EXPECT_EQ(std::string(signature + 1, 3), "PNG");
    EXPECT_THROW(writeSlicePng(t, parseSliceSpec("x=7"), dir.file("off.png")), Error);
    EXPECT_FALSE(std::filesystem::exists(dir.file("off.png")));
    EXPECT_THROW(parseSliceSpec("w=1"), Error);
    EXPECT_THROW(parseSliceSpec("z=abc"), Error);
}

TEST(Inspection, ForeignLevelSetIsSummarisedWithoutNodes)
{
    test::ScratchDir dir;
    initializeOpenVdb();
    const float radius = 1.5f, vox = 0.05f;
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, {0.5f, 0, 0}, vox);
    sphere->setName("phi");  // the asset's grid name, but none of its metadata
    openvdb::io::File(dir.file("foreign.vdb")).write({sphere});
    const InspectionTarget t = openForInspection(dir.file("foreign.vdb"));
    EXPECT_FALSE(t.asset);
    EXPECT_EQ(t.gridName, "phi");
    const InspectionReport r = inspect(t);
    EXPECT_EQ(r.nodeCount, 0u);
    const double area = 4 * kPi * radius * radius;
    EXPECT_NEAR(r.levelSetArea, area, 0.5 * vox / radius * area);
    EXPECT_NEAR(0.5 * (r.worldMin.x() + r.worldMax.x()), 0.5, 2 * vox);  // centre found
}

// Found by review: inspection opened a file with OpenVDB before checking lsdem's seal, so a
// damaged asset crashed it (double free, bad_alloc) or printed OpenVDB's own text. An asset is
// now refused as loadAsset refuses it, even with the seal's key itself damaged.
TEST(Inspection, DamagedAssetIsRefusedAsLoadAssetRefusesIt)
{
    test::ScratchDir dir;
    bakedSphere(dir, 1.0, 0.2);
    const std::string bytes = test::readFile(dir.file("s.vdb"));
    const auto write = [&](const std::string& name, const std::string& content) {
        std::ofstream(dir.file(name), std::ios::binary) << content;
        return dir.file(name);
    };
    std::string renamedSeal = bytes.substr(0, 2000);
    const size_t key = renamedSeal.find("lsdem_sha256");
    ASSERT_NE(key, std::string::npos);
    renamedSeal[key] = 'L';
    std::string otherUuid = bytes;
    otherUuid[30] = static_cast<char>(otherUuid[30] ^ 0x01);  // in the header's file UUID
    for (const std::string& path : {write("truncated.vdb", bytes.substr(0, 2000)),
                                    write("uuid.vdb", otherUuid),
                                    write("renamed-seal.vdb", renamedSeal)}) {
        std::string loadMessage;
        try {
            loadAsset(path);
        } catch (const Error& e) {
            loadMessage = e.what();
        }
        ASSERT_FALSE(loadMessage.empty()) << path;
        try {
            openForInspection(path);
            ADD_FAILURE() << path << " was opened";
        } catch (const Error& e) {
            EXPECT_EQ(e.what(), loadMessage);
            EXPECT_EQ(e.problem().find("OpenVDB"), std::string::npos) << e.what();
        }
    }
}
