// Mass properties of closed meshes against closed forms, and the principal frame convention.
#include "lsdem/ls/AnalyticShape.h"
#include "lsdem/ls/MassProperties.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace lsdem;

namespace {

TriangleMesh irregularTetrahedron()
{
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {3, 0, 0}, {0.5, 2, 0}, {0.7, 0.4, 1.3}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    return m;
}

} // namespace

TEST(MassProperties, BoxMeshIsExact)
{
    // A polyhedral box is integrated exactly, whatever its triangulation.
    TriangleMesh box = AnalyticShape::box(1, 2, 3).surfaceMesh(0.35);
    transformMesh(box, Mat3::Identity(), Vec3(10, -5, 7));
    const MassProperties p = computeMassProperties(box);
    EXPECT_NEAR(p.volume, 6.0, 1e-12);
    EXPECT_NEAR((p.centroid - Vec3(10, -5, 7)).norm(), 0.0, 1e-12);
    const Vec3 expected = 6.0 / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4);
    EXPECT_NEAR((p.inertia.diagonal() - expected).norm(), 0.0, 1e-10);
    EXPECT_NEAR(p.inertia(0, 1), 0.0, 1e-10);
}

TEST(MassProperties, TetrahedronMatchesVertexFormulas)
{
    // Volume |det|/6 and centroid = mean of the vertices, for any tetrahedron.
    const TriangleMesh t = irregularTetrahedron();
    const MassProperties p = computeMassProperties(t);
    Mat3 edges;
    edges << t.vertices[1] - t.vertices[0], t.vertices[2] - t.vertices[0],
        t.vertices[3] - t.vertices[0];
    EXPECT_NEAR(p.volume, std::abs(edges.determinant()) / 6.0, 1e-12);
    const Vec3 mean = (t.vertices[0] + t.vertices[1] + t.vertices[2] + t.vertices[3]) / 4.0;
    EXPECT_NEAR((p.centroid - mean).norm(), 0.0, 1e-12);
    // Covariance of a tetrahedron: V/20 (Σ d_i d_i^T + s s^T) with d_i about the centroid and
    // s = Σ d_i = 0, so the inertia is tr(C) I - C with C = V/20 Σ d_i d_i^T.
    Mat3 c = Mat3::Zero();
    for (const Vec3& v : t.vertices) c += (v - mean) * (v - mean).transpose();
    c *= p.volume / 20.0;
    const Mat3 inertia = c.trace() * Mat3::Identity() - c;
    EXPECT_NEAR((p.inertia - inertia).norm(), 0.0, 1e-12);
}

TEST(MassProperties, RotatedCopyLandsInTheSamePrincipalFrame)
{
    const TriangleMesh a = irregularTetrahedron();
    const PrincipalFrame fa = principalFrame(computeMassProperties(a), a);
    EXPECT_NEAR(fa.rotation.determinant(), 1.0, 1e-12);
    EXPECT_LE(fa.moments[0], fa.moments[1]);
    EXPECT_LE(fa.moments[1], fa.moments[2]);

    const Mat3 q = Eigen::AngleAxisd(1.1, Vec3(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
    TriangleMesh b = a;
    transformMesh(b, q, Vec3(4, 5, -6));
    const PrincipalFrame fb = principalFrame(computeMassProperties(b), b);
    // x_asset = R (x - c): the same vertex must land on the same asset-frame point.
    for (size_t i = 0; i < a.vertices.size(); ++i) {
        const Vec3 pa = fa.rotation * (a.vertices[i] - fa.centroid);
        const Vec3 pb = fb.rotation * (b.vertices[i] - fb.centroid);
        EXPECT_NEAR((pa - pb).norm(), 0.0, 1e-9);
    }
    // The principal frame diagonalises the inertia.
    const Mat3 diag = fa.rotation * computeMassProperties(a).inertia * fa.rotation.transpose();
    EXPECT_NEAR(diag(0, 1), 0.0, 1e-10);
    EXPECT_NEAR(diag(1, 2), 0.0, 1e-10);
}

TEST(MassProperties, SquarePlateKeepsItsInputAxesInTheDegeneratePlane)
{
    // Equal moments about x and y: any in-plane axes are principal; lsdem keeps the input's so
    // flat faces stay aligned with the voxel grid.
    const TriangleMesh plate = AnalyticShape::box(2, 2, 0.5).surfaceMesh(0.25);
    const PrincipalFrame f = principalFrame(computeMassProperties(plate), plate);
    const Mat3 absRot = f.rotation.cwiseAbs();
    EXPECT_NEAR((absRot - Mat3::Identity()).norm(), 0.0, 1e-9);
}
