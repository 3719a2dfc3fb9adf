#include "MeshPartCrossing.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <tuple>
#include <utility>

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

bool boxesOverlap(const MeshPart& a, const MeshPart& b)
{
    return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

} // namespace

std::optional<PartCrossing> findPartCrossing(const TriangleMesh& mesh,
                                             const std::vector<MeshPart>& parts)
{
    // Only parts whose box meets another part's box can cross; their triangles are boxed once
    // and swept together, pairs within one part skipped (each part's neighbours overlap).
    std::vector<int> partOf(mesh.triangles.size(), -1);
    std::vector<Box> boxes;
    for (size_t i = 0; i < parts.size(); ++i) {
        bool meetsAnother = false;
        for (size_t j = 0; j < parts.size() && !meetsAnother; ++j)
            meetsAnother = j != i && boxesOverlap(parts[i], parts[j]);
        if (!meetsAnother) continue;
        for (int t : *parts[i].triangles) {
            partOf[static_cast<size_t>(t)] = static_cast<int>(i);
            CGAL::Bbox_3 box;
            for (int v : mesh.triangles[static_cast<size_t>(t)])
                box += point(mesh.vertices[static_cast<size_t>(v)]).bbox();
            boxes.emplace_back(box, t);
        }
    }
    // The least crossing (by parts, then triangles), so the answer does not depend on the
    // order in which the sweep meets them.
    std::optional<PartCrossing> least;
    auto key = [](const PartCrossing& c) {
        return std::make_tuple(c.partA, c.partB, c.triangleA, c.triangleB);
    };
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        int a = x.info(), b = y.info();
        int partA = partOf[static_cast<size_t>(a)], partB = partOf[static_cast<size_t>(b)];
        if (partA == partB) return;
        if (partA > partB) std::swap(a, b), std::swap(partA, partB);
        const PartCrossing candidate{partA, partB, a, b};
        if (least && key(*least) <= key(candidate)) return;
        // (Exactly flat triangles were dropped before; the exact test needs none.)
        const auto ta = triangle(mesh, a), tb = triangle(mesh, b);
        if (ta.is_degenerate() || tb.is_degenerate()) return;
        if (CGAL::do_intersect(ta, tb)) least = candidate;
    });
    return least;
}

} // namespace lsdem
