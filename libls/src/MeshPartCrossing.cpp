#include "MeshPartCrossing.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

namespace lsdem {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Kernel::Point_3 point(const Vec3& v) { return Kernel::Point_3(v.x(), v.y(), v.z()); }

Kernel::Triangle_3 triangle(const TriangleMesh& mesh, int t)
{
    const auto& tri = mesh.triangles[static_cast<size_t>(t)];
    return Kernel::Triangle_3(point(mesh.vertices[static_cast<size_t>(tri[0])]),
                              point(mesh.vertices[static_cast<size_t>(tri[1])]),
                              point(mesh.vertices[static_cast<size_t>(tri[2])]));
}

std::vector<Box> boxesOf(const TriangleMesh& mesh, const MeshPart& part)
{
    std::vector<Box> boxes;
    boxes.reserve(part.triangles->size());
    for (int t : *part.triangles) {
        const auto& tri = mesh.triangles[static_cast<size_t>(t)];
        CGAL::Bbox_3 box;
        for (int v : tri) box += point(mesh.vertices[static_cast<size_t>(v)]).bbox();
        boxes.emplace_back(box, t);
    }
    return boxes;
}

bool boxesOverlap(const MeshPart& a, const MeshPart& b)
{
    return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

} // namespace

std::optional<PartCrossing> findPartCrossing(const TriangleMesh& mesh,
                                             const std::vector<MeshPart>& parts)
{
    for (size_t i = 0; i < parts.size(); ++i)
        for (size_t j = i + 1; j < parts.size(); ++j) {
            if (!boxesOverlap(parts[i], parts[j])) continue;
            std::vector<Box> a = boxesOf(mesh, parts[i]), b = boxesOf(mesh, parts[j]);
            std::optional<PartCrossing> found;
            // Triangles whose boxes meet are tested exactly; the first pair that meets is kept.
            CGAL::box_intersection_d(a.begin(), a.end(), b.begin(), b.end(),
                                     [&](const Box& x, const Box& y) {
                                         if (found) return;
                                         // (Exactly flat triangles were dropped before; the
                                         // exact test needs none.)
                                         const auto tx = triangle(mesh, x.info()),
                                                    ty = triangle(mesh, y.info());
                                         if (tx.is_degenerate() || ty.is_degenerate()) return;
                                         if (CGAL::do_intersect(tx, ty))
                                             found = PartCrossing{int(i), int(j), x.info(),
                                                                  y.info()};
                                     });
            if (found) return found;
        }
    return std::nullopt;
}

} // namespace lsdem
