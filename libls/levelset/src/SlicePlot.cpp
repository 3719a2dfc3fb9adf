#include "lsdem/ls/SlicePlot.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace lsdem {

SliceSpec parseSliceSpec(const std::string& text)
{
    SliceSpec spec;
    if (text.size() < 3 || text[1] != '=' || text[0] < 'x' || text[0] > 'z')
        throw Error("", "--slice wants AXIS=VALUE with AXIS x, y or z (e.g. z=0), got '" +
                            text + "'");
    spec.axis = text[0] - 'x';
    char* end = nullptr;
    spec.value = std::strtod(text.c_str() + 2, &end);
    if (*end != '\0' || !std::isfinite(spec.value))
        throw Error("", "--slice: '" + text.substr(2) + "' is not a number");
    return spec;
}

namespace {

struct Rgb
{
    unsigned char r, g, b;
};

/// Diverging map: -1 → blue, 0 → white, +1 → red (values clamped).
Rgb diverging(double t)
{
    t = std::max(-1.0, std::min(1.0, t));
    const double a = std::abs(t);
    const auto fade = [&](double full) { return static_cast<unsigned char>(255 * (1 - a) + full * a); };
    return t < 0 ? Rgb{fade(40), fade(80), fade(200)} : Rgb{fade(200), fade(50), fade(40)};
}

void writePng(const std::string& path, int width, int height, const std::vector<Rgb>& pixels)
{
    writeFileAtomically(path, [&](const std::string& tmp) {
        FILE* fp = std::fopen(tmp.c_str(), "wb");
        if (!fp) throw Error(path, "cannot open the image for writing");
        png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
        png_infop info = png ? png_create_info_struct(png) : nullptr;
        if (!png || !info || setjmp(png_jmpbuf(png))) {
            png_destroy_write_struct(&png, &info);
            std::fclose(fp);
            throw Error(path, "libpng failed to write the image");
        }
        png_init_io(png, fp);
        png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (int y = 0; y < height; ++y)
            png_write_row(png, reinterpret_cast<png_const_bytep>(&pixels[size_t(y) * width]));
        png_write_end(png, nullptr);
        png_destroy_write_struct(&png, &info);
        if (std::fclose(fp) != 0) throw Error(path, "could not finish writing the image");
    });
}

} // namespace

void writeSlicePng(const InspectionTarget& target, const SliceSpec& slice,
                   const std::string& pngPath)
{
    const LevelSetGrid& ls = *target.levelSet;
    const openvdb::CoordBBox box = ls.grid->evalActiveVoxelBoundingBox();
    Vec3 lo, hi;
    for (int k = 0; k < 3; ++k) {
        lo[k] = ls.origin[k] + ls.voxelSize * box.min()[k];
        hi[k] = ls.origin[k] + ls.voxelSize * box.max()[k];
    }
    if (slice.value < lo[slice.axis] || slice.value > hi[slice.axis])
        throw Error(pngPath, "the plane " + std::string(1, char('x' + slice.axis)) + "=" +
                                 numberText(slice.value) + " misses the grid, which spans " +
                                 numberText(lo[slice.axis]) + " to " + numberText(hi[slice.axis]),
                    "choose a coordinate inside that range");
    // Image axes: u to the right, v up, with (axis, u, v) cyclic.
    const int u = (slice.axis + 1) % 3, v = (slice.axis + 2) % 3;
    const double spanU = hi[u] - lo[u], spanV = hi[v] - lo[v];
    const double pixel = std::max(spanU, spanV) / slice.maxPixels;
    const int width = std::max(1, int(std::ceil(spanU / pixel)));
    const int height = std::max(1, int(std::ceil(spanV / pixel)));
    const double scale = std::abs(ls.grid->background());

    LevelSetSampler sampler(ls);
    std::vector<double> phi(size_t(width) * height);
    auto pointAt = [&](int x, int y) {
        Vec3 p;
        p[slice.axis] = slice.value;
        p[u] = lo[u] + (x + 0.5) * pixel;
        p[v] = hi[v] - (y + 0.5) * pixel;  // image rows go down
        return p;
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) phi[size_t(y) * width + x] = sampler.phi(pointAt(x, y));

    // Inside is shaded by depth relative to the deepest point shown, outside by the band
    // width, so both halves use the whole colour range.
    double deepest = 0.0;
    for (double value : phi) deepest = std::min(deepest, value);
    std::vector<Rgb> pixels(phi.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            pixels[i] = diverging(phi[i] < 0 ? phi[i] / -deepest : phi[i] / scale);
            // Zero contour: a sign change to the right or below.
            const bool right = x + 1 < width && (phi[i] < 0) != (phi[i + 1] < 0);
            const bool below = y + 1 < height && (phi[i] < 0) != (phi[i + width] < 0);
            if (right || below) pixels[i] = {0, 0, 0};
        }
    if (target.asset) {
        // Nodes within one node spacing of the plane, as small green squares.
        const double reach = std::max(target.asset->spacing.mean, ls.voxelSize);
        for (const Vec3& p : target.asset->nodes.positions) {
            if (std::abs(p[slice.axis] - slice.value) > 0.5 * reach) continue;
            const int cx = int((p[u] - lo[u]) / pixel), cy = int((hi[v] - p[v]) / pixel);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = cx + dx, y = cy + dy;
                    if (x >= 0 && x < width && y >= 0 && y < height)
                        pixels[size_t(y) * width + x] = {20, 160, 40};
                }
        }
    }
    writePng(pngPath, width, height, pixels);
}

} // namespace lsdem
