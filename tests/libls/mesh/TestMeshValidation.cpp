// Tests of validateSolidMesh: what it refuses (with which message), and what it repairs.
#include "lsdem/core/Error.h"
#include "lsdem/mesh/MeshValidation.h"

#include "support/TestMeshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

using lsdem::MeshValidationReport;
using lsdem::TriangleMesh;
using lsdem::Vec3;

namespace {

using lsdem::test::makeBox;
using lsdem::test::mergeWelded;
using lsdem::test::reversed;
using lsdem::test::makeIcosphere;
using lsdem::test::signedVolume;

void flip(std::array<int, 3>& tri) { std::swap(tri[1], tri[2]); }

using Corner = std::array<double, 3>;
using Face = std::array<Corner, 3>;

/// The triangles as position triples, each rotated to start at its smallest corner (which
/// keeps its orientation), sorted: equal lists mean the same oriented surface.
std::vector<Face> canonical(const TriangleMesh& mesh)
{
    std::vector<Face> faces;
    for (const auto& t : mesh.triangles) {
        Face f;
        for (int k = 0; k < 3; ++k) {
            const Vec3& v = mesh.vertices[t[k]];
            f[k] = {v.x(), v.y(), v.z()};
        }
        std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
        faces.push_back(f);
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

/// Run validation, expect an lsdem::Error naming the source, and return its message.
std::string validationError(TriangleMesh mesh)
{
    const std::string source = "input/grain.stl";
    try {
        lsdem::validateSolidMesh(mesh, source);
    } catch (const lsdem::Error& e) {
        EXPECT_EQ(e.where(), source);
        EXPECT_NE(std::string(e.what()).find(source), std::string::npos) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no lsdem::Error thrown";
    return "";
}

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

const TriangleMesh kCube = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));

TEST(MeshValidation, AcceptsAClosedOutwardCubeUnchanged)
{
    ASSERT_DOUBLE_EQ(signedVolume(kCube), 1.0);
    TriangleMesh mesh = kCube;
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "cube");
    EXPECT_EQ(report.removedDegenerateTriangles, 0);
    EXPECT_EQ(report.reorientedTriangles, 0);
    EXPECT_FALSE(report.flippedToOutward);
    EXPECT_EQ(mesh.triangles, kCube.triangles);
    EXPECT_EQ(mesh.vertices, kCube.vertices);
}

TEST(MeshValidation, RefusesAnEmptyMesh)
{
    EXPECT_CONTAINS(validationError(TriangleMesh{}), "no triangles");
    TriangleMesh onlyVertices;
    onlyVertices.vertices = kCube.vertices;
    EXPECT_CONTAINS(validationError(onlyVertices), "no triangles");
}

TEST(MeshValidation, RefusesAnOpenSurfaceCountingBoundaryEdges)
{
    // Each edge of a closed mesh has two triangles; removing one triangle leaves its three
    // edges with one triangle each.
    TriangleMesh mesh = kCube;
    mesh.triangles.erase(mesh.triangles.begin() + 5);
    const std::string message = validationError(mesh);
    EXPECT_CONTAINS(message, "open surface: 3 boundary edges");
    EXPECT_CONTAINS(message, "Close Holes");

    // Removing a whole square face (two triangles) opens its 4 sides.
    TriangleMesh face = kCube;
    face.triangles.assign(kCube.triangles.begin() + 2, kCube.triangles.end());
    EXPECT_CONTAINS(validationError(face), "open surface: 4 boundary edges");
}

TEST(MeshValidation, RefusesTwoCubesSharingAnEdge)
{
    // The edge x = y = 1 is an edge of both cubes, so four triangles meet there.
    const TriangleMesh pair = mergeWelded(kCube, makeBox(Vec3(1, 1, 0), Vec3(2, 2, 1)));
    ASSERT_EQ(pair.vertices.size(), 14u);
    EXPECT_CONTAINS(validationError(pair), "non-manifold surface: 1 edge shared");
}

TEST(MeshValidation, RefusesADuplicatedTriangle)
{
    // A copy of a triangle puts three triangles on each of its three edges.
    TriangleMesh mesh = kCube;
    mesh.triangles.push_back(mesh.triangles[0]);
    EXPECT_CONTAINS(validationError(mesh), "non-manifold surface: 3 edges");
}

TEST(MeshValidation, TurnsAnInsideOutCubeOutward)
{
    TriangleMesh mesh = reversed(kCube);
    ASSERT_DOUBLE_EQ(signedVolume(mesh), -1.0);
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "cube");
    EXPECT_TRUE(report.flippedToOutward);
    EXPECT_EQ(report.reorientedTriangles, 0);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 1.0);
    EXPECT_EQ(canonical(mesh), canonical(kCube));
}

TEST(MeshValidation, ReorientsIndividuallyFlippedTriangles)
{
    // Triangle 0 is where the search starts: flipping it must not make the other eleven
    // count as the odd ones out.
    TriangleMesh mesh = kCube;
    flip(mesh.triangles[0]);
    flip(mesh.triangles[7]);
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "cube");
    EXPECT_EQ(report.reorientedTriangles, 2);
    EXPECT_FALSE(report.flippedToOutward);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 1.0);
    EXPECT_EQ(canonical(mesh), canonical(kCube));
}

TEST(MeshValidation, ReorientsAndTurnsOutwardTogether)
{
    // Inside-out with one triangle disagreeing: one reorientation, then a global flip.
    TriangleMesh mesh = reversed(kCube);
    flip(mesh.triangles[3]);
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "cube");
    EXPECT_EQ(report.reorientedTriangles, 1);
    EXPECT_TRUE(report.flippedToOutward);
    EXPECT_EQ(canonical(mesh), canonical(kCube));
}

TEST(MeshValidation, DropsDegenerateTriangles)
{
    TriangleMesh mesh = kCube;
    mesh.triangles.push_back({2, 2, 5});  // repeated vertex
    // A second copy of corner 0, displaced so little that the triangle (0, copy, 1) has an
    // area of 5e-15, below 1e-12 times the mean triangle area (6 / 14).
    mesh.vertices.push_back(mesh.vertices[0] + Vec3(0, 0, 1e-14));
    mesh.triangles.push_back({0, 8, 1});
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "cube");
    EXPECT_EQ(report.removedDegenerateTriangles, 2);
    EXPECT_EQ(canonical(mesh), canonical(kCube));
    EXPECT_EQ(mesh.vertices.size(), 9u);  // the now unused copy may stay
}

TEST(MeshValidation, KeepsThinButRealTriangles)
{
    // Displaced by 1e-6 the extra triangle has area 5e-7, a real sliver: it is kept, and its
    // edges to the copy have one triangle each, so the surface is open.
    TriangleMesh mesh = kCube;
    mesh.vertices.push_back(mesh.vertices[0] + Vec3(0, 0, 1e-6));
    mesh.triangles.push_back({0, 8, 1});
    EXPECT_CONTAINS(validationError(mesh), "open surface: 2 boundary edges");
}

TEST(MeshValidation, DegeneracyIsRelativeToTheMeshSize)
{
    // A 1 nm cube has triangles of area 5e-19; none of them is degenerate.
    TriangleMesh mesh = makeBox(Vec3(0, 0, 0), Vec3(1e-9, 1e-9, 1e-9));
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "tiny");
    EXPECT_EQ(report.removedDegenerateTriangles, 0);
    EXPECT_NEAR(signedVolume(mesh), 1e-27, 1e-40);
}

TEST(MeshValidation, RefusesAMeshOfOnlyZeroAreaTriangles)
{
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 2, 1}, {3, 3, 0}};  // collinear, and a repeated vertex
    EXPECT_CONTAINS(validationError(mesh), "zero area");
}

TEST(MeshValidation, SaysWhenDroppedTrianglesLeaveTheSurfaceOpen)
{
    // A cube missing one triangle, with a degenerate one in the list: the hole stays.
    TriangleMesh cube = kCube;
    cube.triangles.erase(cube.triangles.begin());
    cube.triangles.push_back({0, 0, 0});
    const std::string message = validationError(cube);
    EXPECT_CONTAINS(message, "3 boundary edges");
    EXPECT_CONTAINS(message, "after dropping 1 degenerate triangle");
}

TEST(MeshValidation, RefusesNonFiniteCoordinatesNamingTheVertex)
{
    TriangleMesh mesh = kCube;
    mesh.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
    std::string message = validationError(mesh);
    EXPECT_CONTAINS(message, "vertex 3");
    EXPECT_CONTAINS(message, "nan");

    mesh = kCube;
    mesh.vertices[6].z() = -std::numeric_limits<double>::infinity();
    message = validationError(mesh);
    EXPECT_CONTAINS(message, "vertex 6");
    EXPECT_CONTAINS(message, "-inf");

    // Unused vertices count too: bounds are taken over all of them.
    mesh = kCube;
    mesh.vertices.emplace_back(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0);
    EXPECT_CONTAINS(validationError(mesh), "vertex 8");
}

TEST(MeshValidation, RefusesIndicesOutOfRange)
{
    TriangleMesh mesh = kCube;
    mesh.triangles[4][1] = 8;
    std::string message = validationError(mesh);
    EXPECT_CONTAINS(message, "triangle 4");
    EXPECT_CONTAINS(message, "vertex 8");
    mesh.triangles[4][1] = -1;
    EXPECT_CONTAINS(validationError(mesh), "vertex -1");
}

TEST(MeshValidation, RefusesANonOrientableClosedSurface)
{
    // The 6-vertex projective plane (half an icosahedron with opposite points identified):
    // every edge has exactly two triangles, but no consistent orientation exists.
    TriangleMesh mesh;
    for (int i = 0; i < 6; ++i)
        mesh.vertices.emplace_back(std::cos(i), std::sin(2 * i), 0.3 * i * i);
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                      {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
    EXPECT_CONTAINS(validationError(mesh), "cannot be oriented");
}

TEST(MeshValidation, RefusesASurfaceEnclosingNoVolume)
{
    // Two copies of a triangle back to back: closed, manifold, orientable, but flat.
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 1}};
    EXPECT_CONTAINS(validationError(mesh), "encloses no volume");
}

TEST(MeshValidation, RefusesAFlatPartBesideASolidOne)
{
    // A sheet (a triangle and its reverse) next to a cube: the total volume is the cube's,
    // but the sheet bounds nothing.
    TriangleMesh sheet;
    sheet.vertices = {{5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
    sheet.triangles = {{0, 1, 2}, {0, 2, 1}};
    const std::string message = validationError(mergeWelded(kCube, sheet));
    EXPECT_CONTAINS(message, "(2 triangles) encloses no volume");
}

TEST(MeshValidation, TurnsEachSeparatePartOutward)
{
    // Two disjoint unit cubes, the second inside-out: only the second is reversed.
    const TriangleMesh right = makeBox(Vec3(2, 0, 0), Vec3(3, 1, 1));
    TriangleMesh mesh = mergeWelded(kCube, reversed(right));
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "two cubes");
    EXPECT_TRUE(report.flippedToOutward);
    EXPECT_EQ(report.reorientedTriangles, 0);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 2.0);
    EXPECT_EQ(canonical(mesh), canonical(mergeWelded(kCube, right)));
}

TEST(MeshValidation, KeepsACavityInward)
{
    // A 3^3 block with a 1^3 cavity: the cavity's surface faces into the hole (negative
    // volume on its own), which is right, so nothing changes and the volume is 27 - 1.
    const TriangleMesh outer = makeBox(Vec3(0, 0, 0), Vec3(3, 3, 3));
    const TriangleMesh cavity = reversed(makeBox(Vec3(1, 1, 1), Vec3(2, 2, 2)));
    TriangleMesh mesh = mergeWelded(outer, cavity);
    const TriangleMesh original = mesh;
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "hollow");
    EXPECT_FALSE(report.flippedToOutward);
    EXPECT_EQ(report.reorientedTriangles, 0);
    EXPECT_EQ(mesh.triangles, original.triangles);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 26.0);
}

TEST(MeshValidation, TurnsAnInsideOutHollowBlockOutwardWithItsCavity)
{
    const TriangleMesh outer = makeBox(Vec3(0, 0, 0), Vec3(3, 3, 3));
    const TriangleMesh cavity = reversed(makeBox(Vec3(1, 1, 1), Vec3(2, 2, 2)));
    const TriangleMesh good = mergeWelded(outer, cavity);
    TriangleMesh mesh = reversed(good);
    const MeshValidationReport report = lsdem::validateSolidMesh(mesh, "hollow");
    EXPECT_TRUE(report.flippedToOutward);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 26.0);
    EXPECT_EQ(canonical(mesh), canonical(good));
}

TEST(MeshValidation, RefusesOverlappingParts)
{
    // A clump of two unit cubes exported without a union: the overlap (0.5 × 0.75 × 0.75)
    // would count twice in the volume (2 instead of 1.72), and the inner faces would leave a
    // false surface inside the grain's level set.
    TriangleMesh mesh = mergeWelded(kCube, makeBox(Vec3(0.5, 0.25, 0.25), Vec3(1.5, 1.25, 1.25)));
    const std::string message = validationError(mesh);
    EXPECT_CONTAINS(message, "two parts of the surface (12 triangles and 12 triangles) cross or touch");
    EXPECT_CONTAINS(message, "boolean union");
}

TEST(MeshValidation, RefusesPartsThatCrossWithNoCornerInsideTheOther)
{
    // Two bars crossing like a plus sign: no corner of either lies inside the other, only
    // their faces cross.
    const TriangleMesh along = makeBox(Vec3(0, 1, 1), Vec3(3, 2, 2));
    const TriangleMesh across = makeBox(Vec3(1, 0, 0.5), Vec3(2, 3, 2.5));
    EXPECT_CONTAINS(validationError(mergeWelded(along, across)), "cross or touch");
}

TEST(MeshValidation, AcceptsPartsApartAndPartsNestedWithoutTouching)
{
    TriangleMesh apart = mergeWelded(kCube, makeBox(Vec3(1.001, 0, 0), Vec3(2, 1, 1)));
    EXPECT_NO_THROW(lsdem::validateSolidMesh(apart, "apart"));
    // A block with a cavity and a smaller block inside the cavity (a rattler).
    TriangleMesh nested = mergeWelded(
        mergeWelded(makeBox(Vec3(0, 0, 0), Vec3(5, 5, 5)),
                    reversed(makeBox(Vec3(1, 1, 1), Vec3(4, 4, 4)))),
        makeBox(Vec3(2, 2, 2), Vec3(3, 3, 3)));
    lsdem::validateSolidMesh(nested, "nested");
    EXPECT_DOUBLE_EQ(signedVolume(nested), 125.0 - 27.0 + 1.0);
}

} // namespace
