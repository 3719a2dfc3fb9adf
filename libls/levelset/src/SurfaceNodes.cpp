#include "lsdem/ls/SurfaceNodes.h"

#include "lsdem/core/PointHashGrid.h"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace lsdem {

double SurfaceNodes::totalArea() const
{
    return std::accumulate(areas.begin(), areas.end(), 0.0);
}

SurfaceNodes nodesFromMesh(const TriangleMesh& mesh, AreaRule rule)
{
    const size_t nv = mesh.vertices.size();
    std::vector<double> area(nv, 0.0);
    std::vector<Vec3> normal(nv, Vec3::Zero());
    std::vector<char> used(nv, 0);
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
        const auto& tri = mesh.triangles[t];
        const double third = triangleArea(mesh, t) / 3.0;
        const Vec3& p0 = mesh.vertices[tri[0]];
        const Vec3 faceNormal =
            (mesh.vertices[tri[1]] - p0).cross(mesh.vertices[tri[2]] - p0).normalized();
        for (int k = 0; k < 3; ++k) {
            const int v = tri[k];
            const Vec3 e1 = (mesh.vertices[tri[(k + 1) % 3]] - mesh.vertices[v]).normalized();
            const Vec3 e2 = (mesh.vertices[tri[(k + 2) % 3]] - mesh.vertices[v]).normalized();
            // Angle weighting makes the vertex normal independent of how faces are split.
            const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
            normal[v] += angle * faceNormal;
            area[v] += third;
            used[v] = 1;
        }
    }
    SurfaceNodes nodes;
    for (size_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        nodes.positions.push_back(mesh.vertices[v]);
        nodes.normals.push_back(normal[v].normalized());
        nodes.areas.push_back(area[v]);
    }
    if (rule == AreaRule::Uniform && !nodes.areas.empty()) {
        const double mean = nodes.totalArea() / static_cast<double>(nodes.size());
        std::fill(nodes.areas.begin(), nodes.areas.end(), mean);
    }
    return nodes;
}

namespace {

/// Interleave the low 21 bits of x, y, z into a 63-bit Morton code.
uint64_t mortonCode(uint32_t x, uint32_t y, uint32_t z)
{
    auto spread = [](uint64_t v) {
        v &= 0x1fffff;
        v = (v | v << 32) & 0x1f00000000ffffULL;
        v = (v | v << 16) & 0x1f0000ff0000ffULL;
        v = (v | v << 8) & 0x100f00f00f00f00fULL;
        v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
        v = (v | v << 2) & 0x1249249249249249ULL;
        return v;
    };
    return spread(x) | spread(y) << 1 | spread(z) << 2;
}

} // namespace

void sortNodesSpatially(SurfaceNodes& nodes, double cellSize)
{
    const size_t n = nodes.size();
    if (n == 0) return;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    for (const Vec3& p : nodes.positions) lo = lo.cwiseMin(p);
    std::vector<uint64_t> code(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3 cell = (nodes.positions[i] - lo) / cellSize;
        code[i] = mortonCode(static_cast<uint32_t>(cell.x()), static_cast<uint32_t>(cell.y()),
                             static_cast<uint32_t>(cell.z()));
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return code[a] < code[b]; });
    SurfaceNodes sorted;
    const bool withNormals = nodes.hasNormals();
    for (size_t i : order) {
        sorted.positions.push_back(nodes.positions[i]);
        if (withNormals) sorted.normals.push_back(nodes.normals[i]);
        sorted.areas.push_back(nodes.areas[i]);
    }
    nodes = std::move(sorted);
}

NodeSpacing nodeSpacing(const SurfaceNodes& nodes)
{
    NodeSpacing stats;
    const size_t n = nodes.size();
    if (n < 2) return stats;
    // Hash grid with cells of about the mean spacing; search growing shells of cells until
    // the shell is farther than the best distance found.
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : nodes.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double cell = std::max(std::sqrt(std::max(nodes.totalArea(), 1e-300) / n),
                                 1e-9 * (hi - lo).norm());
    const PointHashGrid grid(nodes.positions, cell);
    const int maxShell = grid.cellsAcross() + 1;

    // Each node's nearest neighbour in parallel (the grid is only read), then the sums in
    // node order: the same numbers on any thread count.
    std::vector<double> nearest(n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        const Vec3& p = nodes.positions[i];
        const Eigen::Vector3i c = grid.cellOf(p);
        double best = std::numeric_limits<double>::infinity();
        for (int shell = 0; shell <= maxShell; ++shell) {
            if ((shell - 1) * cell > best) break;
            for (int dx = -shell; dx <= shell; ++dx)
                for (int dy = -shell; dy <= shell; ++dy)
                    for (int dz = -shell; dz <= shell; ++dz) {
                        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != shell)
                            continue;
                        const std::vector<int>* inCell = grid.nodesIn(c + Eigen::Vector3i(dx, dy, dz));
                        if (!inCell) continue;
                        for (int j : *inCell)
                            if (j != int(i)) best = std::min(best, (nodes.positions[j] - p).norm());
                    }
        }
        nearest[i] = best;
    });
    double sum = 0.0;
    stats.min = std::numeric_limits<double>::infinity();
    stats.max = 0.0;
    for (const double best : nearest) {
        sum += best;
        stats.min = std::min(stats.min, best);
        stats.max = std::max(stats.max, best);
    }
    stats.mean = sum / n;
    return stats;
}

namespace {

/// Cut the (spatially sorted) @a positions into runs of at most @a runSize with bounding
/// spheres; @a patchSide is the side of a typical run's patch of surface.
std::vector<NodeBlock> runsWithSpheres(const std::vector<Vec3>& positions, int runSize,
                                       double patchSide)
{
    std::vector<NodeBlock> blocks;
    const int n = static_cast<int>(positions.size());
    if (n == 0) return blocks;
    // A Z-order curve jumps now and then; a run that spans a jump would get a large sphere.
    // So a run also ends where its bounding box would grow beyond 1.5 times the side of its
    // patch.
    const double widest = 1.5 * patchSide;
    auto close = [&](int begin, int end) {
        NodeBlock b;
        b.begin = begin;
        b.end = end;
        Vec3 lo = positions[begin], hi = lo;
        for (int i = begin; i < end; ++i) {
            lo = lo.cwiseMin(positions[i]);
            hi = hi.cwiseMax(positions[i]);
        }
        b.center = 0.5 * (lo + hi);
        for (int i = begin; i < end; ++i)
            b.radius = std::max(b.radius, (positions[i] - b.center).norm());
        blocks.push_back(b);
    };
    int begin = 0;
    Vec3 lo = positions[0], hi = lo;
    for (int i = 1; i < n; ++i) {
        const Vec3 newLo = lo.cwiseMin(positions[i]);
        const Vec3 newHi = hi.cwiseMax(positions[i]);
        if (i - begin >= runSize || (newHi - newLo).maxCoeff() > widest) {
            close(begin, i);
            begin = i;
            lo = hi = positions[i];
        } else {
            lo = newLo;
            hi = newHi;
        }
    }
    close(begin, n);
    return blocks;
}

} // namespace

NodeBlocks groupNodesIntoBlocks(const SurfaceNodes& nodes, int blockSize, int clusterSize)
{
    NodeBlocks result;
    const int n = static_cast<int>(nodes.size());
    if (n == 0) return result;
    const double area = std::max(nodes.totalArea(), 1e-300);
    result.blocks =
        runsWithSpheres(nodes.positions, blockSize, std::sqrt(area * blockSize / n));
    // Clusters: runs of block centres, each cluster's sphere then widened to hold its blocks.
    std::vector<Vec3> centers;
    for (const NodeBlock& b : result.blocks) centers.push_back(b.center);
    result.clusters = runsWithSpheres(centers, clusterSize,
                                      std::sqrt(area * blockSize * clusterSize / n));
    for (NodeBlock& c : result.clusters) {
        c.radius = 0.0;
        for (int k = c.begin; k < c.end; ++k) {
            const NodeBlock& b = result.blocks[static_cast<size_t>(k)];
            c.radius = std::max(c.radius, (b.center - c.center).norm() + b.radius);
        }
    }
    return result;
}

} // namespace lsdem
