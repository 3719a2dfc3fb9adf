#include "lsdem/ls/MassProperties.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>

namespace lsdem {

MassProperties computeMassProperties(const TriangleMesh& mesh)
{
    // Integrate about a reference point on the mesh to keep round-off small for meshes far
    // from the origin; each triangle and the reference point span a signed tetrahedron.
    const Vec3 ref = mesh.vertices.empty() ? Vec3::Zero() : mesh.vertices[mesh.triangles[0][0]];
    double volume = 0.0;
    Vec3 firstMoment = Vec3::Zero();
    Mat3 secondMoment = Mat3::Zero();  // ∫ x x^T dV about ref
    for (const auto& tri : mesh.triangles) {
        const Vec3 a = mesh.vertices[tri[0]] - ref;
        const Vec3 b = mesh.vertices[tri[1]] - ref;
        const Vec3 c = mesh.vertices[tri[2]] - ref;
        const double v = a.dot(b.cross(c)) / 6.0;
        const Vec3 sum = a + b + c;
        volume += v;
        firstMoment += v * sum / 4.0;
        // ∫ over the tetrahedron (0,a,b,c) of x x^T = v/20 (a a^T + b b^T + c c^T + s s^T).
        secondMoment += v / 20.0 *
                        (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                         sum * sum.transpose());
    }
    MassProperties props;
    props.volume = volume;
    if (volume == 0.0) return props;
    const Vec3 centroidFromRef = firstMoment / volume;
    props.centroid = ref + centroidFromRef;
    const Mat3 central = secondMoment - volume * centroidFromRef * centroidFromRef.transpose();
    props.inertia = central.trace() * Mat3::Identity() - central;
    return props;
}

namespace {

/// Third moment of surface area along @a axis about @a centre (triangle-centroid rule: exact
/// covariance under rotation of the mesh, which is all the sign convention needs).
double areaSkewness(const TriangleMesh& mesh, const Vec3& centre, const Vec3& axis)
{
    double skew = 0.0;
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3 mid =
            (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.0;
        const double s = (mid - centre).dot(axis);
        skew += triangleArea(mesh, t) * s * s * s;
    }
    return skew;
}

} // namespace

PrincipalFrame principalFrame(const MassProperties& props, const TriangleMesh& mesh)
{
    PrincipalFrame frame;
    frame.centroid = props.centroid;
    Eigen::SelfAdjointEigenSolver<Mat3> solver(props.inertia);
    frame.moments = solver.eigenvalues();  // ascending
    Mat3 axes = solver.eigenvectors();     // columns

    const double scale = std::max(std::abs(frame.moments.maxCoeff()), 1e-300);
    const double tol = 1e-7 * scale;
    const bool equal01 = std::abs(frame.moments[1] - frame.moments[0]) < tol;
    const bool equal12 = std::abs(frame.moments[2] - frame.moments[1]) < tol;
    if (equal01 && equal12) {
        // Isotropic inertia (sphere, cube): every frame is principal; keep the input's axes.
        frame.rotation = Mat3::Identity();
        frame.moments = Vec3::Constant(props.inertia.trace() / 3.0);
        return frame;
    }
    if (equal01 || equal12) {
        // Axisymmetric inertia (square block, spheroid): the unique axis is fixed; in the
        // degenerate plane take the input axis that lies closest to it, so flat faces stay
        // aligned with the grid when the input was aligned.
        const int unique = equal01 ? 2 : 0;
        const Vec3 u = axes.col(unique);
        Vec3 best = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
            const Vec3 projected = Vec3::Unit(k) - Vec3::Unit(k).dot(u) * u;
            if (projected.norm() > best.norm() + 1e-12) best = projected;
        }
        best.normalize();
        if (unique == 2) {  // (best, u x best, u)
            axes.col(0) = best;
            axes.col(1) = u.cross(best);
        } else {            // (u, best, u x best)
            axes.col(0) = u;
            axes.col(1) = best;
        }
    } else {
        // Distinct moments: axes fixed up to sign; make the area skewness along the first two
        // non-negative so a rotated copy of the same shape lands in the same frame.
        const double area = surfaceArea(mesh);
        const double length = std::cbrt(std::max(props.volume, 1e-300));
        for (int k = 0; k < 2; ++k) {
            const double skew = areaSkewness(mesh, props.centroid, axes.col(k));
            if (std::abs(skew) > 1e-9 * area * length * length * length && skew < 0.0)
                axes.col(k) = -axes.col(k);
        }
    }
    axes.col(2) = axes.col(0).cross(axes.col(1));  // right-handed
    frame.rotation = axes.transpose();
    return frame;
}

} // namespace lsdem
