// Generated grains: reproducible to the byte, closed manifold outward meshes whatever the
// options, the requested volume, an exact ellipsoid when the roughness is zero, the roughness
// as the RMS of the log-radius, log-normal sizes, and files that read back.
#include "lsdem/ls/GrainGenerator.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/mesh/MeshValidation.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace lsdem;

namespace {

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(GrainGenerator, SameSeedGivesTheSameBytesAndOtherSeedsOtherGrains)
{
    test::ScratchDir dir;
    GrainShapeOptions o;
    o.triangles = 500;
    o.maxDegree = 8;
    o.sizeSpread = 0.3;
    for (const char* ext : {".stl", ".obj"}) {
        writeGrainMesh(generateGrain(o, 7, 3), dir.file(std::string("a") + ext));
        writeGrainMesh(generateGrain(o, 7, 3), dir.file(std::string("b") + ext));
        writeGrainMesh(generateGrain(o, 8, 3), dir.file(std::string("c") + ext));
        writeGrainMesh(generateGrain(o, 7, 4), dir.file(std::string("d") + ext));
        const std::string a = fileBytes(dir.file(std::string("a") + ext));
        EXPECT_GT(a.size(), 1000u);
        EXPECT_EQ(a, fileBytes(dir.file(std::string("b") + ext)));
        EXPECT_NE(a, fileBytes(dir.file(std::string("c") + ext)));
        EXPECT_NE(a, fileBytes(dir.file(std::string("d") + ext)));
    }
}

TEST(GrainGenerator, MeshesAreValidSolidsOfTheRequestedVolume)
{
    // Corners of the option space: rough and angular, smooth, flat and long, fine and coarse.
    std::vector<GrainShapeOptions> cases(4);
    cases[0].roughness = 0.4, cases[0].decay = 0.5, cases[0].maxDegree = 12;
    cases[0].triangles = 1500;
    cases[1].roughness = 0.05, cases[1].decay = 3.0, cases[1].triangles = 2000;
    cases[2].elongation = 0.4, cases[2].flatness = 0.3, cases[2].maxDegree = 6;
    cases[2].triangles = 320;
    cases[3].size = 2.5, cases[3].sizeSpread = 0.5, cases[3].maxDegree = 20;
    cases[3].triangles = 3000;
    for (size_t c = 0; c < cases.size(); ++c)
        for (uint64_t i = 0; i < 5; ++i) {
            TriangleMesh mesh = generateGrain(cases[c], 11, i);
            const MeshValidationReport r = validateSolidMesh(mesh, "grain");
            EXPECT_EQ(r.removedDegenerateTriangles, 0);
            EXPECT_EQ(r.reorientedTriangles, 0);
            EXPECT_FALSE(r.flippedToOutward);
            const double d = generatedGrainSize(cases[c], 11, i);
            EXPECT_NEAR(computeMassProperties(mesh).volume / (kPi * d * d * d / 6.0), 1.0, 1e-12)
                << "case " << c << " grain " << i;
        }
}

TEST(GrainGenerator, ZeroRoughnessIsAnEllipsoidOfTheGivenRatios)
{
    GrainShapeOptions o;
    o.roughness = 0.0;
    o.elongation = 0.7;
    o.flatness = 0.5;
    const TriangleMesh mesh = generateGrain(o, 1, 0);
    // Every vertex on x² + (y/e)² + (z/(e f))² = a²: the same a for all.
    const double e = o.elongation, ef = o.elongation * o.flatness;
    auto level = [&](const Vec3& v) {
        return std::sqrt(v.x() * v.x() + v.y() * v.y() / (e * e) + v.z() * v.z() / (ef * ef));
    };
    const double a = level(mesh.vertices[0]);
    for (const Vec3& v : mesh.vertices) EXPECT_NEAR(level(v) / a, 1.0, 1e-12);
    // The inscribed polyhedron holds a little less than the ellipsoid (about 1 % at 2000
    // triangles), and its volume is the sphere of diameter 1's.
    const double ellipsoid = 4.0 / 3.0 * kPi * a * (a * e) * (a * ef);
    EXPECT_GT(ellipsoid, kPi / 6.0);
    EXPECT_LT(ellipsoid, 1.02 * kPi / 6.0);
}

TEST(GrainGenerator, RoughnessIsTheRmsOfTheLogRadius)
{
    GrainShapeOptions o;
    o.elongation = o.flatness = 1.0;
    o.roughness = 0.2;
    o.maxDegree = 8;
    o.triangles = 20000;  // fine: the vertices sample the sphere nearly uniformly
    for (uint64_t i = 0; i < 3; ++i) {
        const TriangleMesh mesh = generateGrain(o, 5, i);
        // f = ln r - mean(ln r), averaged over the vertices (area-weighted by their nearly
        // equal icosphere cells: the weights differ by < 20 %, hence the tolerance).
        double mean = 0.0, square = 0.0;
        for (const Vec3& v : mesh.vertices) mean += std::log(v.norm());
        mean /= double(mesh.vertices.size());
        for (const Vec3& v : mesh.vertices) square += std::pow(std::log(v.norm()) - mean, 2);
        const double rms = std::sqrt(square / double(mesh.vertices.size()));
        EXPECT_NEAR(rms, o.roughness, 0.05 * o.roughness) << "grain " << i;
    }
}

TEST(GrainGenerator, SizesAreLogNormalAroundTheMedian)
{
    GrainShapeOptions o;
    o.size = 2.0;
    o.sizeSpread = 0.25;
    const int n = 4000;
    double sum = 0.0, square = 0.0;
    for (int i = 0; i < n; ++i) {
        const double l = std::log(generatedGrainSize(o, 3, uint64_t(i)));
        sum += l, square += l * l;
    }
    const double mean = sum / n, sd = std::sqrt(square / n - mean * mean);
    // 4 standard errors: σ/√n for the mean, σ/√(2n) for the standard deviation.
    EXPECT_NEAR(mean, std::log(o.size), 4 * o.sizeSpread / std::sqrt(n));
    EXPECT_NEAR(sd, o.sizeSpread, 4 * o.sizeSpread / std::sqrt(2.0 * n));
    o.sizeSpread = 0.0;
    EXPECT_EQ(generatedGrainSize(o, 3, 17), 2.0);
}

TEST(GrainGenerator, FilesReadBackAsTheMesh)
{
    test::ScratchDir dir;
    GrainShapeOptions o;
    o.triangles = 320;
    o.maxDegree = 6;
    const TriangleMesh mesh = generateGrain(o, 2, 0);
    for (const char* name : {"g.stl", "g.obj"}) {
        writeGrainMesh(mesh, dir.file(name));
        TriangleMesh back = readMesh(dir.file(name));
        ASSERT_EQ(back.triangles.size(), mesh.triangles.size()) << name;
        ASSERT_EQ(back.vertices.size(), mesh.vertices.size()) << name;
        EXPECT_NO_THROW(validateSolidMesh(back, name));
        // float32 (STL) or 7 digits (OBJ): volume to about 1e-6.
        EXPECT_NEAR(computeMassProperties(back).volume / computeMassProperties(mesh).volume, 1.0,
                    1e-5)
            << name;
    }
    EXPECT_THROW(writeGrainMesh(mesh, dir.file("g.ply")), Error);
    EXPECT_EQ(dir.entryCount(), 2u);
}

TEST(GrainGenerator, OptionsOutOfRangeNameTheOption)
{
    auto message = [](GrainShapeOptions o) {
        try {
            checkGrainShapeOptions(o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    GrainShapeOptions o;
    EXPECT_EQ(message(o), "");
    auto bad = o;
    bad.elongation = 1.5;
    EXPECT_NE(message(bad).find("--elongation"), std::string::npos);
    bad = o, bad.flatness = 0.0;
    EXPECT_NE(message(bad).find("--flatness"), std::string::npos);
    bad = o, bad.roughness = std::nan("");
    EXPECT_NE(message(bad).find("--roughness"), std::string::npos);
    bad = o, bad.size = -1;
    EXPECT_NE(message(bad).find("--size"), std::string::npos);
    bad = o, bad.size = 1e40;  // float32 files: infinities
    EXPECT_NE(message(bad).find("--size"), std::string::npos);
    bad = o, bad.size = 1e-50;  // float32 files: zeros
    EXPECT_NE(message(bad).find("--size"), std::string::npos);
    bad = o, bad.maxDegree = 40, bad.triangles = 500;
    EXPECT_NE(message(bad).find("--triangles"), std::string::npos);
}
