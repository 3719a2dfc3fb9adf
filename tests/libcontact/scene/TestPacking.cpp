// The packing generator: the box or a cylinder filled with the mixture asked for, no two grains
// overlapping by more than a stated tolerance, every grain inside the container, the same seed
// giving the same packing bit for bit (and another seed another one), buried grains left where
// they are (the bounded cost of a layer), a count that cannot fit reported with what did, and
// a catalogue read as a mixture named as a scene's asset set names it.
#include "lsdem/scene/Packing.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/scene/CatalogMixture.h"
#include "lsdem/scene/SceneFile.h"
#include "support/TestSupport.h"
#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/GrainsCsv.h"
#include "lsdem/simulation/GrainOverlaps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

using namespace lsdem;

namespace {

std::shared_ptr<const GrainAsset> bake(const AnalyticShape& shape)
{
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = 150;
    std::vector<std::string> warnings;
    return std::make_shared<const GrainAsset>(bakeAnalytic(shape, o, warnings));
}

PackingOptions smallPacking(uint64_t seed)
{
    static const std::shared_ptr<const GrainAsset> ball = bake(AnalyticShape::sphere(1.0));
    static const std::shared_ptr<const GrainAsset> egg =
        bake(AnalyticShape::ellipsoid(1.2, 0.8, 0.6));
    PackingOptions o;
    o.mixture = {{"ball", ball, 2.0}, {"egg", egg, 1.0}};
    o.boxMin = Vec3(0, 0, 0);
    o.boxMax = Vec3(6, 6, 7);
    o.count = 12;
    o.seed = seed;
    return o;
}

/// The deepest grain–grain overlap of @a scene / the smaller bounding radius, measured with the
/// level sets independently of the generator's own report.
double deepestOverlap(const Scene& scene)
{
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    double deepest = 0.0;
    for (const GrainOverlap& v : findGrainOverlaps(w))
        deepest = std::max(deepest, v.depth / std::min(w.grains[size_t(v.first)].asset->boundingRadius,
                                                       w.grains[size_t(v.second)].asset->boundingRadius));
    return deepest;
}

} // namespace

// 12 grains, 2:1 balls to eggs, in a 6 × 6 × 7 box. At rest the deposition presses grains
// into each other by about 1 % of their bounding radius (by design: Packing.h); the bound
// checked is 3 %, below the 5 % a scene's [[grain_files]] allows by default, so the packing
// reads back into a scene.
TEST(Packing, FillsTheBoxWithTheMixtureWithoutOverlaps)
{
    const PackingOptions o = smallPacking(7);
    const PackingResult r = generatePacking(o);
    std::cout << "[ measured ] packing of 12: " << r.layers << " layers, " << r.steps
              << " steps, " << r.seconds << " s, solid fraction " << r.solidFraction
              << ", deepest overlap " << r.maxOverlap << " of the smaller radius\n";
    ASSERT_TRUE(r.complete);
    ASSERT_EQ(r.scene.grains.size(), 12u);
    EXPECT_EQ(r.unsettledLayers, 0);
    int balls = 0;
    double volume = 0.0;
    for (const GrainSpec& g : r.scene.grains) {
        balls += g.asset == 0 ? 1 : 0;
        volume += o.mixture[size_t(g.asset)].asset->mass.volume;
        // Inside the box: the centre at least the shape's least half-extent from a side wall
        // (an egg may lie on its flattest side against it), less the walls' own contact
        // overlap, at most the 3 % of the bounding radius allowed between grains below. (It
        // was half the bounding radius, 0.606 for the egg, more than its least half-extent.)
        const double least = g.asset == 0 ? 1.0 : 0.6;  // ball 1; egg 1.2 × 0.8 × 0.6
        const double inner = least - 0.03 * o.mixture[size_t(g.asset)].asset->boundingRadius;
        for (int d = 0; d < 2; ++d) {
            EXPECT_GT(g.pose.position[d], o.boxMin[d] + inner);
            EXPECT_LT(g.pose.position[d], o.boxMax[d] - inner);
        }
        EXPECT_GT(g.pose.position.z(), o.boxMin.z());
        EXPECT_LT(g.pose.position.z(), o.boxMax.z());
    }
    EXPECT_EQ(balls, 8);
    EXPECT_NEAR(r.solidFraction, volume / (6.0 * 6.0 * 7.0), 1e-12);
    // Overlaps measured independently of the generator's own report.
    std::vector<std::string> warnings;
    const World w = buildWorld(r.scene, warnings);
    double deepest = 0.0;
    for (const GrainOverlap& v : findGrainOverlaps(w))
        deepest = std::max(deepest, v.depth / std::min(w.grains[size_t(v.first)].asset->boundingRadius,
                                                       w.grains[size_t(v.second)].asset->boundingRadius));
    EXPECT_LT(deepest, 0.03);
    EXPECT_DOUBLE_EQ(deepest, r.maxOverlap);
    // Gravity did its work: the grains rest on the floor or on each other, not where inserted.
    double highest = 0.0;
    for (const GrainSpec& g : r.scene.grains) highest = std::max(highest, g.pose.position.z());
    EXPECT_LT(highest, 4.5);
}

TEST(Packing, SameSeedSamePackingBitForBit)
{
    auto pack = [](uint64_t seed) {
        PackingOptions o = smallPacking(seed);
        o.count = 6;
        o.settleTolerance = 1e-3;  // rest is not the point here: keep it short
        return generatePacking(o);
    };
    const PackingResult a = pack(11), b = pack(11), c = pack(12);
    const std::string ta = grainsCsvText(a.scene, 0, a.scene.grains.size());
    EXPECT_EQ(ta, grainsCsvText(b.scene, 0, b.scene.grains.size()));
    EXPECT_NE(ta, grainsCsvText(c.scene, 0, c.scene.grains.size()));
}

// Balls of diameter 2 in a 2.5 × 2.5 × 3 box: one fits, a second cannot be put above it.
TEST(Packing, ACountThatCannotFitSaysWhatDid)
{
    PackingOptions o = smallPacking(1);
    o.mixture.resize(1);
    o.boxMax = Vec3(2.5, 2.5, 3.0);
    o.count = 5;
    const PackingResult r = generatePacking(o);
    EXPECT_FALSE(r.complete);
    EXPECT_EQ(r.scene.grains.size(), 1u);
    EXPECT_NEAR(r.solidFraction, o.mixture[0].asset->mass.volume / (2.5 * 2.5 * 3.0), 1e-12);
}

TEST(Packing, BadOptionsAreRefused)
{
    PackingOptions o = smallPacking(1);
    o.boxMax = Vec3(6, 0, 7);
    EXPECT_THROW(generatePacking(o), Error);
    o = smallPacking(1);
    o.mixture[0].fraction = -1.0;
    EXPECT_THROW(generatePacking(o), Error);
    o = smallPacking(1);
    o.count = 0;
    EXPECT_THROW(generatePacking(o), Error);
    o.count = 1000000000000;
    EXPECT_THROW(generatePacking(o), Error);
    o = smallPacking(1);
    o.cylinder = PackingCylinder{0, 0, 0.0, 0, 5};
    EXPECT_THROW(generatePacking(o), Error);
    o.cylinder = PackingCylinder{0, 0, 3.0, 5, 5};
    EXPECT_THROW(generatePacking(o), Error);
    o.cylinder = PackingCylinder{0, 0, 0.9, 0, 5};  // narrower than a ball
    EXPECT_THROW(generatePacking(o), Error);
    // Found by review: friction -1 packed as frictionless, settle -1 ran every layer to the
    // step limit. Refused, naming the option.
    const auto expectRefused = [](const PackingOptions& bad, const std::string& option) {
        try {
            generatePacking(bad);
            ADD_FAILURE() << option << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.problem().rfind(option + " must be a finite number", 0), 0u) << e.what();
            EXPECT_NE(e.fix().find(option), std::string::npos) << e.what();
        }
    };
    for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
        o = smallPacking(1);
        o.friction = bad;
        expectRefused(o, "--friction");
        o = smallPacking(1);
        o.settleTolerance = bad;
        expectRefused(o, "--settle");
    }
    o = smallPacking(1);
    o.settleTolerance = 0.0;  // never met
    expectRefused(o, "--settle");
    o = smallPacking(1);
    o.boxMax = Vec3(1.5, 6, 7);  // narrower than a ball
    try {
        generatePacking(o);
        ADD_FAILURE() << "a grain larger than the box was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
    }
}

// The same mixture in a vertical cylinder of about the box's cross-section: every node of every
// grain inside the cylinder up to the walls' own contact overlap (the deposition presses grains
// into the wall as into each other: about 1 % of the bounding radius by design; 3 % checked, as
// between grains), no overlaps beyond 3 %, and the same seed gives the same packing.
TEST(Packing, FillsACylinderWithoutOverlapsAndWithinItsWall)
{
    PackingOptions o = smallPacking(5);
    PackingCylinder c;
    c.x = 1.0;
    c.y = -2.0;
    c.radius = 3.4;
    c.zMin = 0.5;
    c.zMax = 7.5;
    o.cylinder = c;
    const PackingResult r = generatePacking(o);
    ASSERT_TRUE(r.complete);
    ASSERT_EQ(r.scene.grains.size(), 12u);
    EXPECT_EQ(r.unsettledLayers, 0);
    double volume = 0.0, deepestOut = 0.0, highest = 0.0;
    for (const GrainSpec& g : r.scene.grains) {
        const GrainAsset& a = *o.mixture[size_t(g.asset)].asset;
        volume += a.mass.volume;
        for (const Vec3& node : a.nodes.positions) {
            const Vec3 x = g.pose.toWorld(node);
            const double outside = std::hypot(x.x() - c.x, x.y() - c.y) - c.radius;
            deepestOut = std::max(deepestOut, outside / a.boundingRadius);
            EXPECT_GT(x.z(), c.zMin - 0.03 * a.boundingRadius);
        }
        highest = std::max(highest, g.pose.position.z());
    }
    std::cout << "[ measured ] cylinder packing of 12: deepest node outside the wall "
              << deepestOut << " of the bounding radius, deepest overlap " << r.maxOverlap << "\n";
    EXPECT_LT(deepestOut, 0.03);
    EXPECT_NEAR(r.solidFraction, volume / (kPi * c.radius * c.radius * 7.0), 1e-12);
    EXPECT_LT(deepestOverlap(r.scene), 0.03);
    EXPECT_LT(highest, 5.0);  // deposited, not left where inserted

    o.count = 6;
    o.settleTolerance = 1e-3;
    const PackingResult a = generatePacking(o), b = generatePacking(o);
    EXPECT_EQ(grainsCsvText(a.scene, 0, 6), grainsCsvText(b.scene, 0, 6));
}

// A tall column of balls, layer after layer: once a grain lies deeper than kFreeDepthDiameters
// largest diameters below a new layer's bottom it does not move any more (bit for bit), the
// depositions hold fewer grains than the packing, and the packing is as sound as a small one.
TEST(Packing, BuriedGrainsStayPutSoALayerCostsBoundedWork)
{
    PackingOptions o = smallPacking(3);
    o.mixture.resize(1);
    o.boxMax = Vec3(4.5, 4.5, 30.0);
    o.count = 36;
    std::vector<Scene> afterLayer;
    const PackingResult r =
        generatePacking(o, [&](const PackingResult& p) { afterLayer.push_back(p.scene); });
    ASSERT_TRUE(r.complete);
    ASSERT_GE(r.layers, 5);
    EXPECT_EQ(r.unsettledLayers, 0);
    EXPECT_LT(r.largestLayerGrains, 36);
    const double diameter = 2.0 * o.mixture[0].asset->boundingRadius;
    long long heldGrains = 0;
    for (size_t layer = 1; layer < afterLayer.size(); ++layer) {
        const Scene& before = afterLayer[layer - 1];
        double bedTop = 0.0;
        for (const GrainSpec& g : before.grains)
            bedTop = std::max(bedTop, g.pose.position.z() + 0.5 * diameter);
        for (size_t i = 0; i < before.grains.size(); ++i) {
            if (before.grains[i].pose.position.z() > bedTop - kFreeDepthDiameters * diameter)
                continue;
            ++heldGrains;
            EXPECT_EQ(afterLayer[layer].grains[i].pose.position, before.grains[i].pose.position);
            EXPECT_EQ(afterLayer[layer].grains[i].pose.orientation.coeffs(),
                      before.grains[i].pose.orientation.coeffs());
        }
    }
    EXPECT_GT(heldGrains, 0);
    std::cout << "[ measured ] column of 36: " << r.layers << " layers, at most "
              << r.largestLayerGrains << " grains per deposition, deepest overlap " << r.maxOverlap
              << "\n";
    EXPECT_LT(deepestOverlap(r.scene), 0.03);
    // Inside the box up to the walls' contact overlap, within the same 3 % of the radius
    // (wedged between two side walls, balls press into them by about 1 %).
    for (const GrainSpec& g : r.scene.grains)
        for (int d = 0; d < 2; ++d) {
            EXPECT_GT(g.pose.position[d], o.boxMin[d] + 0.97 * 0.5 * diameter);
            EXPECT_LT(g.pose.position[d], o.boxMax[d] - 0.97 * 0.5 * diameter);
        }
}

// A catalogue (as lsdem-bake --out-dir writes it: name and asset columns, asset paths relative
// to its folder) becomes a mixture named SET/NAME; packed and written, the table reads into a
// scene whose [asset_sets.SET] reads the same catalogue.
TEST(Packing, ACatalogueMixtureReadsBackIntoAScene)
{
    const test::ScratchDir dir;
    std::filesystem::create_directories(dir.file("assets/baked"));
    saveAsset(*smallPacking(1).mixture[0].asset, dir.file("assets/baked/ball.vdb"));
    saveAsset(*smallPacking(1).mixture[1].asset, dir.file("assets/baked/egg.vdb"));
    std::ofstream(dir.file("assets/catalog.csv"))
        << "name,asset,volume\nball,baked/ball.vdb,4.18\negg,baked/egg.vdb,2.41\n";
    PackingOptions o = smallPacking(4);
    o.mixture = catalogMixture(dir.file("assets/catalog.csv"), "sand");
    ASSERT_EQ(o.mixture.size(), 2u);
    EXPECT_FALSE(o.mixture[0].asset->nodes.hasNormals());  // loaded for packing only
    EXPECT_EQ(o.mixture[0].name, "sand/ball");
    EXPECT_EQ(o.mixture[1].name, "sand/egg");
    o.count = 4;
    o.settleTolerance = 1e-3;
    const PackingResult r = generatePacking(o);
    ASSERT_TRUE(r.complete);
    writeGrainsCsv(r.scene, 0, 4, dir.file("packing.csv"));
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
[simulation]
time_step = 1e-6
end_steps = 1
)";
    const Scene s = readSceneFile(dir.file("scene.toml"));
    ASSERT_EQ(s.grains.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(s.assets[size_t(s.grains[i].asset)].name,
                  o.mixture[size_t(r.scene.grains[i].asset)].name);
        EXPECT_LT((s.grains[i].pose.position - r.scene.grains[i].pose.position).norm(), 1e-12);
    }
    std::vector<std::string> warnings;
    EXPECT_EQ(buildWorld(s, warnings).grains.size(), 4u);  // the overlap check passes

    // Bad catalogues: named, with a fix.
    for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
             {"name,asset\nball,baked/none.vdb\n", "file not found"},
             // Loaded in parallel, the first bad row is still the one reported.
             {"name,asset\nball,assets/baked/ball.vdb\nfake,bad.csv\negg,assets/baked/egg.vdb\n"
              "gone,assets/baked/none.vdb\n",
              "asset 'fake': "},
             {"name,asset\n", "lists no assets"},
             {"name,volume\nball,1\n", "asset"}}) {
        std::ofstream(dir.file("bad.csv")) << text;
        try {
            catalogMixture(dir.file("bad.csv"), "sand");
            ADD_FAILURE() << text << ": accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.csv"), std::string::npos) << e.what();
            EXPECT_FALSE(e.fix().empty()) << e.what();
            // One fix, not the asset's own under the catalogue's (found by review).
            EXPECT_EQ(std::string(e.what()).find("fix:"), std::string(e.what()).rfind("fix:"))
                << e.what();
        }
    }
    EXPECT_THROW(catalogMixture(dir.file("nowhere.csv"), "sand"), Error);
    EXPECT_THROW(catalogMixture(dir.file("assets/catalog.csv"), "a/b"), Error);
    EXPECT_THROW(catalogMixture(dir.file("assets/catalog.csv"), ""), Error);
}
