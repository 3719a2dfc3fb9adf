// Grain measures against an ellipsoid's closed forms, and the catalogue file: what is written
// reads back bit for bit, and bad catalogues are refused with the file, line and column.
#include "lsdem/ls/GrainCatalog.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

TEST(GrainCatalog, MeasuresOfAnEllipsoidMatchItsClosedForms)
{
    const double a = 2.0, b = 1.5, c = 1.0;
    const AnalyticShape shape = AnalyticShape::ellipsoid(a, b, c);
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.08;
    std::vector<std::string> warnings;
    const GrainMeasures m = measureGrain(bakeAnalytic(shape, o, warnings));
    const double volume = 4.0 / 3.0 * kPi * a * b * c;
    EXPECT_NEAR(m.volume, volume, 1e-12 * volume);
    EXPECT_NEAR(m.equivalentDiameter, 2.0 * std::cbrt(a * b * c), 1e-12);
    // Nodes on the exact surface, spaced h: the node mesh's area is short by O(h²) (about
    // 0.1 % here), and the extreme nodes fall short of the poles by at most ~h²/(2 ρ), ρ the
    // smallest radius of curvature there (c²/a = 0.5): under 1 % of each length.
    EXPECT_NEAR(m.surfaceArea / shape.surfaceArea(), 1.0, 0.005);
    EXPECT_NEAR(m.lengthLong / (2 * a), 1.0, 0.01);
    EXPECT_NEAR(m.lengthIntermediate / (2 * b), 1.0, 0.01);
    EXPECT_NEAR(m.lengthShort / (2 * c), 1.0, 0.01);
    EXPECT_NEAR(m.elongation, b / a, 0.01);
    EXPECT_NEAR(m.flatness, c / b, 0.01);
    const double sphericity =
        kPi * std::pow(6.0 * volume / kPi, 2.0 / 3.0) / shape.surfaceArea();
    EXPECT_NEAR(m.sphericity, sphericity, 0.005);
}

TEST(GrainCatalog, WhatIsWrittenReadsBackBitForBit)
{
    test::ScratchDir dir;
    CatalogEntry e;
    e.name = "grain, with comma";
    e.asset = "grain.vdb";
    e.source = "scans/\"odd\".stl";
    e.sourceSha256 = std::string(64, 'a');
    e.bakeOptions = "voxel-per-size 0.03 nodes 600 areas mesh band 3";
    e.measures.volume = 0.1 + 0.2;  // not a short decimal
    e.measures.surfaceArea = 1.0 / 3.0;
    e.measures.sphericity = 0.9;
    e.nodes = 600;
    e.vdp = 1e-7;
    e.sdp = 123456.789;
    e.bakeSeconds = 0.25;
    CatalogEntry f = e;
    f.name = "second";
    writeCatalog(dir.file("catalog.csv"), {e, f});
    const std::vector<CatalogEntry> back = readCatalog(dir.file("catalog.csv"));
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].name, e.name);
    EXPECT_EQ(back[0].asset, e.asset);
    EXPECT_EQ(back[0].source, e.source);
    EXPECT_EQ(back[0].sourceSha256, e.sourceSha256);
    EXPECT_EQ(back[0].bakeOptions, e.bakeOptions);
    EXPECT_EQ(back[0].measures.volume, e.measures.volume);
    EXPECT_EQ(back[0].measures.surfaceArea, e.measures.surfaceArea);
    EXPECT_EQ(back[0].measures.sphericity, e.measures.sphericity);
    EXPECT_EQ(back[0].nodes, 600);
    EXPECT_EQ(back[0].vdp, e.vdp);
    EXPECT_EQ(back[0].sdp, e.sdp);
    EXPECT_EQ(back[0].bakeSeconds, e.bakeSeconds);
    EXPECT_EQ(back[1].name, "second");
}

TEST(GrainCatalog, BadCataloguesNameTheLineAndColumn)
{
    test::ScratchDir dir;
    struct Case
    {
        std::string text, expected;
    };
    const std::vector<Case> cases = {
        {"", "is empty"},
        {"name,volume\na,1\n", "no column 'asset'"},
        {"asset,volume\na.vdb,1\n", "no column 'name'"},
        {"name,asset,volume\na,a.vdb,1\nb,b.vdb,nan\n", ":3: column 'volume': 'nan'"},
        {"name,asset,volume\na,a.vdb,1x\n", ":2: column 'volume': '1x'"},
        {"name,asset,volume\na,a.vdb\n", ":2: has 2 fields, the header 3"},
        {"name,asset\na,a.vdb\na,b.vdb\n", ":3: a second asset named 'a'"},
        {"name,asset\n,a.vdb\n", ":2: column 'name' is empty"},
        {"name,asset,name\na,a.vdb,b\n", "column 'name' appears twice"},
        {"name,asset,nodes\na,a.vdb,2.5\n", ":2: column 'nodes': '2.5' is not a whole count"},
    };
    for (const Case& c : cases) {
        writeTextFileAtomically(dir.file("catalog.csv"), c.text);
        try {
            readCatalog(dir.file("catalog.csv"));
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos)
                << e.what() << "\nwanted: " << c.expected;
            EXPECT_NE(std::string(e.what()).find("catalog.csv"), std::string::npos);
        }
    }
    // Only name and asset are needed; unknown columns are ignored.
    writeTextFileAtomically(dir.file("catalog.csv"), "asset,name,colour\na.vdb,a,red\n");
    const auto entries = readCatalog(dir.file("catalog.csv"));
    ASSERT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries[0].name, "a");
    EXPECT_EQ(entries[0].asset, "a.vdb");

    // Excel's "CSV UTF-8" starts with a byte-order mark, which is not part of the first column.
    writeTextFileAtomically(dir.file("catalog.csv"), "\xEF\xBB\xBFname,asset\na,a.vdb\n");
    const auto fromExcel = readCatalog(dir.file("catalog.csv"));
    ASSERT_EQ(fromExcel.size(), 1u);
    EXPECT_EQ(fromExcel[0].name, "a");
}
