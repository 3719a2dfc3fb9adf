// The PNG slice of a level set, decoded here with libpng: its size and orientation follow the
// grid's extent and the plane's axes, inside pixels are blue and outside ones red as the exact
// distance says, the black zero contour lies on the surface, and the nodes show as green dots.
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/ls/SlicePlot.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <png.h>

#include <cmath>
#include <vector>

using namespace lsdem;

namespace {

// Voxels of 1/16 over [-1.5, 2.5] × [-1.25, 1.75] × [-0.5, 0.5]: binary fractions, so the
// image geometry below is exact. The unit sphere at the origin sits left of the middle and
// below it.
constexpr double kVoxel = 0.0625;
const Vec3 kOrigin(-1.5, -1.25, -0.5);
constexpr int kCells[3] = {64, 48, 16};
constexpr float kBand = 0.25f;

double exactPhi(const Vec3& p) { return p.norm() - 1.0; }

/// A level set holding the exact distance to the unit sphere at every voxel of the box above
/// (capped at the band), so all of them are active and the slice spans the box.
InspectionTarget sphereTarget()
{
    initializeOpenVdb();
    auto ls = std::make_shared<LevelSetGrid>();
    ls->voxelSize = kVoxel;
    ls->origin = kOrigin;
    const auto grid = openvdb::FloatGrid::create(kBand);
    auto accessor = grid->getAccessor();
    for (int i = 0; i <= kCells[0]; ++i)
        for (int j = 0; j <= kCells[1]; ++j)
            for (int k = 0; k <= kCells[2]; ++k) {
                const double phi = exactPhi(kOrigin + kVoxel * Vec3(i, j, k));
                accessor.setValue(openvdb::Coord(i, j, k), std::min(float(phi), kBand));
            }
    ls->grid = toLevelSetGrid(*grid);
    InspectionTarget t;
    t.path = "sphere";
    t.levelSet = ls;
    return t;
}

struct Image
{
    int width = 0, height = 0;
    std::vector<png_byte> rgb;
    const png_byte* at(int x, int y) const { return &rgb[3 * (size_t(y) * width + x)]; }
};

Image decodePng(const std::string& path)
{
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    Image out;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        ADD_FAILURE() << "not a PNG: " << path << ": " << image.message;
        return out;
    }
    image.format = PNG_FORMAT_RGB;
    out.rgb.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
        ADD_FAILURE() << "cannot decode " << path << ": " << image.message;
        return out;
    }
    out.width = int(image.width);
    out.height = int(image.height);
    return out;
}

} // namespace

// The longest side gets maxPixels; the other follows the grid's extent along the plane's axes,
// (u, v) = (x, y) for z = c, (y, z) for x = c and (z, x) for y = c.
TEST(SlicePlot, ImageSizeFollowsTheGridExtentAlongThePlanesAxes)
{
    test::ScratchDir dir;
    const InspectionTarget t = sphereTarget();
    struct Case { const char* slice; int width, height; };
    // Extents 4 × 3 × 1; pixel = longest / 64. x=0: 3 × 1 → 64 × ceil(64/3) = 22.
    for (const Case c : {Case{"z=0", 64, 48}, Case{"x=0", 64, 22}, Case{"y=0.5", 16, 64}}) {
        SliceSpec spec = parseSliceSpec(c.slice);
        spec.maxPixels = 64;
        writeSlicePng(t, spec, dir.file("slice.png"));
        const Image image = decodePng(dir.file("slice.png"));
        EXPECT_EQ(image.width, c.width) << c.slice;
        EXPECT_EQ(image.height, c.height) << c.slice;
    }
    EXPECT_EQ(dir.entryCount(), 1u);  // written atomically: no temporaries left
}

// Pixel (x, y) of the z = 0 slice is centred at u = -1.5 + (x + ½)/16, v = 1.75 - (y + ½)/16
// (rows go down). The map fades from white to blue (40, 80, 200) inside by depth over the
// deepest pixel, and to red (200, 50, 40) outside by φ over the band, so blue minus red is
// 160·|φ|/deepest inside (±1 for rounding to bytes, ±1 for the interpolation error of
// ~h²/(4r) = 1e-3 in φ) and every pixel whose eight voxels are all beyond the band is exactly
// the full red. Black pixels only on the contour. The box is not symmetric about the sphere,
// so a flipped or transposed image would fail.
TEST(SlicePlot, InsideAndOutsidePixelsAreColouredAsTheLevelSetSays)
{
    test::ScratchDir dir;
    SliceSpec spec = parseSliceSpec("z=0");
    spec.maxPixels = 64;
    writeSlicePng(sphereTarget(), spec, dir.file("slice.png"));
    const Image image = decodePng(dir.file("slice.png"));
    ASSERT_EQ(image.width, 64);
    ASSERT_EQ(image.height, 48);
    const double pixel = kVoxel;
    auto centre = [&](int x, int y) {
        return Vec3(-1.5 + (x + 0.5) * pixel, 1.75 - (y + 0.5) * pixel, 0.0);
    };
    double deepest = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) deepest = std::min(deepest, exactPhi(centre(x, y)));
    int inside = 0, outside = 0, saturated = 0, black = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double phi = exactPhi(centre(x, y));
            const png_byte* c = image.at(x, y);
            if (c[0] == 0 && c[1] == 0 && c[2] == 0) {
                ++black;
                // A sign change to the next pixel: the contour is within one pixel.
                EXPECT_LT(std::abs(phi), 1.1 * pixel) << x << "," << y;
                continue;
            }
            if (phi < -1.1 * pixel) {
                ++inside;
                EXPECT_NEAR(int(c[2]) - int(c[0]), 160 * phi / deepest, 2.5) << x << "," << y;
            } else if (phi > 1.1 * pixel) {
                ++outside;
                EXPECT_GT(c[0], c[2]) << "outside pixel not red at " << x << "," << y;
                if (phi > kBand + std::sqrt(3.0) * kVoxel) {
                    ++saturated;
                    EXPECT_EQ(c[0], 200);
                    EXPECT_EQ(c[1], 50);
                    EXPECT_EQ(c[2], 40);
                }
            }
        }
    // The disc of radius 1 covers π·16² ≈ 804 pixels; the contour is about 2π·16 ≈ 100 long.
    EXPECT_GT(inside, 600);
    EXPECT_GT(outside, 1500);
    EXPECT_GT(saturated, 1000);
    EXPECT_GT(black, 80);
    EXPECT_LT(black, 250);
}

// A baked asset brings its nodes: those near the plane are drawn as green dots on its surface.
TEST(SlicePlot, NodesNearThePlaneShowAsGreenDotsOnTheSurface)
{
    test::ScratchDir dir;
    BakeOptions o;
    o.voxelSize = 0.1;
    o.nodeSpacing = 0.25;
    std::vector<std::string> warnings;
    auto asset = std::make_shared<GrainAsset>(
        bakeAnalytic(AnalyticShape::box(2.0, 1.0, 0.6), o, warnings));
    InspectionTarget t;
    t.asset = asset;
    t.levelSet = asset->levelSet;
    SliceSpec spec = parseSliceSpec("z=0");
    spec.maxPixels = 120;
    writeSlicePng(t, spec, dir.file("nodes.png"));
    const Image image = decodePng(dir.file("nodes.png"));
    ASSERT_GT(image.width, image.height);  // the box is 2 long in x, 1 in y
    // Green pixels lie on the box's outline |x| = 1 or |y| = 0.5 (dots are 3 pixels wide).
    const openvdb::CoordBBox box = t.levelSet->grid->evalActiveVoxelBoundingBox();
    const double loU = t.levelSet->origin.x() + o.voxelSize * box.min().x();
    const double hiV = t.levelSet->origin.y() + o.voxelSize * box.max().y();
    const double spanU = o.voxelSize * (box.max().x() - box.min().x());
    const double pixel = spanU / 120;
    int green = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const png_byte* c = image.at(x, y);
            if (!(c[0] == 20 && c[1] == 160 && c[2] == 40)) continue;
            ++green;
            const double u = loU + (x + 0.5) * pixel, v = hiV - (y + 0.5) * pixel;
            const double outline =
                std::min(std::abs(std::abs(u) - 1.0), std::abs(std::abs(v) - 0.5));
            const bool withinBox = std::abs(u) <= 1.0 + 2 * pixel && std::abs(v) <= 0.5 + 2 * pixel;
            EXPECT_TRUE(withinBox && outline < 2.5 * pixel) << u << "," << v;
        }
    EXPECT_GT(green, 9 * 12);  // the 2 × 1 outline at spacing 0.25: ~24 nodes of 9 pixels
}

TEST(SlicePlot, PlanesOffTheGridAndBadSpecsAreRefused)
{
    test::ScratchDir dir;
    const InspectionTarget t = sphereTarget();
    EXPECT_THROW(writeSlicePng(t, parseSliceSpec("z=0.6"), dir.file("off.png")), Error);
    EXPECT_THROW(writeSlicePng(t, parseSliceSpec("x=-1.6"), dir.file("off.png")), Error);
    try {  // the message names the plane as typed and the grid's span, not "0.600000"
        writeSlicePng(t, parseSliceSpec("z=0.6"), dir.file("off.png"));
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("z=0.6 misses the grid, which spans -0.5 to 0.5"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(dir.entryCount(), 0u);
    const SliceSpec s = parseSliceSpec("y=-1.25");
    EXPECT_EQ(s.axis, 1);
    EXPECT_EQ(s.value, -1.25);
    EXPECT_THROW(parseSliceSpec("z"), Error);
    EXPECT_THROW(parseSliceSpec("z=1x"), Error);
    EXPECT_THROW(parseSliceSpec("z=inf"), Error);
}
