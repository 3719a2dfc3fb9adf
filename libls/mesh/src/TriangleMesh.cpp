#include "lsdem/mesh/TriangleMesh.h"

#include <Eigen/Geometry>

namespace lsdem {

double triangleArea(const TriangleMesh& mesh, int t)
{
    const auto& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    return 0.5 * (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).norm();
}

double surfaceArea(const TriangleMesh& mesh)
{
    double area = 0.0;
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) area += triangleArea(mesh, t);
    return area;
}

void transformMesh(TriangleMesh& mesh, const Mat3& rotation, const Vec3& translation)
{
    for (Vec3& v : mesh.vertices) v = rotation * v + translation;
}

std::array<Vec3, 2> meshBounds(const TriangleMesh& mesh)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (const Vec3& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    return {lo, hi};
}

} // namespace lsdem
