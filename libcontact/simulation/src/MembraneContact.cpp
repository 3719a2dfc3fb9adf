// Grains against a membrane (MembraneContact.h): the triangles binned in a grid, each node
// against the triangles of its cell, the law on the nodes found, and their forces handed to
// the triangles' vertices.
#include "lsdem/simulation/MembraneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/core/Error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace lsdem {

namespace {

/// The barycentric weights of the point of triangle (a, b, c) nearest to @a p: by the
/// Voronoi region of the triangle's vertices, edges or face that @a p lies in.
Vec3 nearestWeights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return Vec3(1, 0, 0);
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return Vec3(0, 1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        return Vec3(1 - v, v, 0);
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return Vec3(0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        return Vec3(1 - w, 0, w);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return Vec3(0, 1 - w, w);
    }
    const double denominator = 1.0 / (va + vb + vc);
    const double v = vb * denominator, w = vc * denominator;
    return Vec3(1 - v - w, v, w);
}

} // namespace

namespace {
/// The skin of the binning, over the reach: wider keeps a binning longer but lists more
/// triangles whose box misses a node (a quarter was the fastest of 0.1 to 1 on a triaxial
/// sample in its membrane).
constexpr double kSkinOverReach = 0.25;
} // namespace

void MembraneTriangleGrid::update(const Membrane& m, double reach)
{
    // (A membrane's triangles keep their vertices through a run: their count tells a new one.)
    bool stale = reach != mReach || m.positions.size() != mBinnedAt.size() ||
                 m.triangles.size() != mBinnedTriangles;
    // One pass over the vertices: a vertex gone to NaN or infinity would make the cells' size
    // meaningless (say so); and a box grown by reach + skin when binned still holds every point
    // within reach of its triangle while no vertex has moved more than the skin along any axis.
    const double skin = kSkinOverReach * reach;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        if (!m.positions[i].allFinite())
            throw Error("membrane '" + m.name + "'",
                        "vertex " + std::to_string(i) + " is no longer at a finite position",
                        "its step is too large for its rubber or its contacts: lower "
                        "[simulation] time_step, or raise its density (mass scaling)");
        stale = stale || !((m.positions[i] - mBinnedAt[i]).cwiseAbs().maxCoeff() <= skin);
    }
    // The normals every time: the contact's depth is measured along them.
    mOutward.resize(m.triangles.size());
    for (size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& v = m.triangles[t].vertices;
        const Vec3 &p0 = m.positions[size_t(v[0])], &p1 = m.positions[size_t(v[1])],
                   &p2 = m.positions[size_t(v[2])];
        mOutward[t] = (p1 - p0).cross(p2 - p0).normalized();
    }
    if (stale) {
        mReach = reach;
        bin(m);
    }
    markLiveCells(m);
}

bool MembraneTriangleGrid::cellRange(int a, double lo, double hi, long long& from,
                                     long long& to) const
{
    const double first = std::floor((lo - mLow[a]) * mInverseCell),
                 last = std::floor((hi - mLow[a]) * mInverseCell);
    if (!(last >= 0.0) || !(first < double(mCells[a]))) return false;
    from = std::max(0LL, static_cast<long long>(first));
    to = std::min(mCells[a] - 1, static_cast<long long>(last));
    return true;
}

void MembraneTriangleGrid::bin(const Membrane& m)
{
    ++mBinnings;
    mBinnedAt = m.positions;
    mBinnedTriangles = m.triangles.size();
    mEntries.clear();
    mCellStart.assign(1, 0);
    mCells[0] = mCells[1] = mCells[2] = 0;
    if (m.triangles.empty()) return;
    const double grow = (1.0 + kSkinOverReach) * mReach;
    std::vector<Entry> boxes;
    boxes.reserve(m.triangles.size());
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    double extent = 0.0;
    for (size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& v = m.triangles[t].vertices;
        Vec3 lo = m.positions[size_t(v[0])], hi = lo;
        for (int k : v) {
            lo = lo.cwiseMin(m.positions[size_t(k)]);
            hi = hi.cwiseMax(m.positions[size_t(k)]);
        }
        lo.array() -= grow;
        hi.array() += grow;
        extent += (hi - lo).maxCoeff();
        low = low.cwiseMin(lo);
        high = high.cwiseMax(hi);
        Entry e;
        e.triangle = int(t);
        for (int a = 0; a < 3; ++a) {  // rounded outward: the float box holds the double one
            e.low[a] = std::nextafter(float(lo[a]), -std::numeric_limits<float>::infinity());
            e.high[a] = std::nextafter(float(hi[a]), std::numeric_limits<float>::infinity());
        }
        boxes.push_back(e);
    }
    // Cells half as wide as the mean grown box: a node's cell then lists few triangles whose
    // box misses it. More cells than a few dozen per triangle would only cost memory (a
    // stretched, sparse membrane): then they are widened.
    mCell = 0.5 * extent / double(boxes.size());
    const double cellsAllowed = 64.0 * double(boxes.size()) + 4096.0;
    for (;;) {
        for (int a = 0; a < 3; ++a)
            mCells[a] = static_cast<long long>(std::floor((high[a] - low[a]) / mCell)) + 1;
        if (double(mCells[0]) * double(mCells[1]) * double(mCells[2]) <= cellsAllowed) break;
        mCell *= 1.25;
    }
    mInverseCell = 1.0 / mCell;
    mLow = low;
    const size_t cells = size_t(mCells[0] * mCells[1] * mCells[2]);
    // Count, then place (a counting sort by cell; in each cell the triangles in index order).
    auto forCellsOf = [&](const Entry& e, auto&& visit) {
        long long from[3], to[3];
        for (int a = 0; a < 3; ++a)
            if (!cellRange(a, double(e.low[a]), double(e.high[a]), from[a], to[a])) return;
        for (long long i = from[0]; i <= to[0]; ++i)
            for (long long j = from[1]; j <= to[1]; ++j)
                for (long long k = from[2]; k <= to[2]; ++k)
                    visit(size_t((i * mCells[1] + j) * mCells[2] + k));
    };
    std::vector<std::uint32_t> count(cells + 1, 0);
    for (const Entry& e : boxes) forCellsOf(e, [&](size_t cell) { ++count[cell + 1]; });
    for (size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
    mCellStart = count;
    mEntries.resize(mCellStart.back());
    for (const Entry& e : boxes) forCellsOf(e, [&](size_t cell) { mEntries[count[cell]++] = e; });
}

void MembraneTriangleGrid::markLiveCells(const Membrane& m)
{
    const size_t cells = mCellStart.size() - 1;
    mLive.assign(cells, 0);
    // A cell is live if its highest point along a triangle's outward normal lies beyond that
    // triangle's plane: (centre − p0)·n + h·(|n_x| + |n_y| + |n_z|) > 0, h half a cell; with a
    // margin of 1e-9 of the terms for their rounding (a node's own depth is rounded too).
    const double half = 0.5 * mCell;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, cells, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t c = range.begin(); c != range.end(); ++c) {
                              if (mCellStart[c] == mCellStart[c + 1]) continue;
                              const long long k = (long long)c % mCells[2],
                                              j = ((long long)c / mCells[2]) % mCells[1],
                                              i = (long long)c / (mCells[1] * mCells[2]);
                              const Vec3 centre =
                                  mLow + mCell * Vec3(double(i) + 0.5, double(j) + 0.5,
                                                      double(k) + 0.5);
                              for (uint32_t e = mCellStart[c]; e < mCellStart[c + 1]; ++e) {
                                  const int t = mEntries[e].triangle;
                                  const Vec3& n = mOutward[size_t(t)];
                                  const Vec3& p0 =
                                      m.positions[size_t(m.triangles[size_t(t)].vertices[0])];
                                  // (a degenerate triangle's normal is zero: no contact)
                                  const Vec3 offset = centre - p0;
                                  const double reachOut = half * n.cwiseAbs().sum();
                                  const double margin =
                                      1e-9 * (offset.cwiseAbs().sum() + reachOut);
                                  if (offset.dot(n) + reachOut + margin > 0.0) {
                                      mLive[c] = 1;
                                      break;
                                  }
                              }
                          }
                      });
}

std::int64_t MembraneTriangleGrid::cellOf(const Vec3& x) const
{
    long long index[3];
    for (int a = 0; a < 3; ++a) {
        const double u = (x[a] - mLow[a]) * mInverseCell;
        if (!(u >= 0.0) || u >= double(mCells[a])) return -1;  // (NaN too)
        index[a] = static_cast<long long>(u);
    }
    const std::int64_t cell = (index[0] * mCells[1] + index[1]) * mCells[2] + index[2];
    return mLive[size_t(cell)] ? cell : -1;
}

bool MembraneTriangleGrid::mayTouch(const Vec3& c, double r) const
{
    if (mEntries.empty()) return false;
    // (widened by 1e-9 of its size and place: a node is placed with rounding)
    r += 1e-9 * (r + c.cwiseAbs().maxCoeff());
    long long from[3], to[3];
    for (int a = 0; a < 3; ++a)
        if (!cellRange(a, c[a] - r, c[a] + r, from[a], to[a])) return false;
    for (long long i = from[0]; i <= to[0]; ++i)
        for (long long j = from[1]; j <= to[1]; ++j) {
            const std::uint8_t* row = mLive.data() + size_t((i * mCells[1] + j) * mCells[2]);
            for (long long k = from[2]; k <= to[2]; ++k)
                if (row[k]) return true;
        }
    return false;
}

void computeMembraneContact(const ContactGrain& grain, const Membrane& m,
                            const MembraneTriangleGrid& grid, const ContactModel& model,
                            double dt, MembraneGrainContact& out, ContactScratch& scratch)
{
    out.result = PairForces();
    out.stats = NodeCheckStats();
    NodeCheckStats& stats = out.stats;
    out.reactions.clear();
    out.stiffness.clear();
    const GrainAsset& a = *grain.asset;
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    if (!grid.mayTouch(grain.pose.position, a.boundingRadius)) {
        stats.nodesCulled += count;
        return;
    }
    std::vector<NodeContact>& contacts = scratch.contacts[0];
    contacts.clear();
    std::vector<MembraneHit>& hits = out.hits;
    hits.clear();
    const Eigen::Matrix3d rotation = grain.pose.orientation.toRotationMatrix();
    const double reach = grid.reach();
    // Neighbouring nodes mostly share a cell: its triangles are looked up once for a run.
    std::int64_t lastCell = -2;
    const MembraneTriangleGrid::Entry *first = nullptr, *last = nullptr;
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + grain.pose.position;
            const std::int64_t cell = grid.cellOf(x);
            if (cell != lastCell) {
                lastCell = cell;
                first = grid.cellBegin(cell);
                last = grid.cellEnd(cell);
            }
            if (first == last) continue;
            ++stats.nodesSampled;
            // A node inside the plane of every triangle near it has depth ≤ 0 at whichever is
            // nearest: it is passed over before the nearest is looked for.
            bool outside = false;
            for (const auto* e = first; e != last && !outside; ++e)
                outside = e->holds(x) &&
                          (x - m.positions[size_t(m.triangles[size_t(e->triangle)].vertices[0])])
                                  .dot(grid.outward(e->triangle)) > 0.0;
            if (!outside) continue;
            // The nearest triangle, ties to the lower index (the same on any thread count).
            double best = std::numeric_limits<double>::infinity();
            MembraneHit hit;
            for (const auto* e = first; e != last; ++e) {
                if (!e->holds(x)) continue;
                const int t = e->triangle;
                const auto& v = m.triangles[size_t(t)].vertices;
                const Vec3 &p0 = m.positions[size_t(v[0])], &p1 = m.positions[size_t(v[1])],
                           &p2 = m.positions[size_t(v[2])];
                const Vec3 w = nearestWeights(x, p0, p1, p2);
                const double distance = (x - (w[0] * p0 + w[1] * p1 + w[2] * p2)).squaredNorm();
                if (distance < best || (distance == best && t < hit.triangle)) {
                    best = distance;
                    hit.triangle = t;
                    hit.weights = w;
                }
            }
            if (!(best <= reach * reach)) continue;
            const Vec3& p0 = m.positions[size_t(m.triangles[size_t(hit.triangle)].vertices[0])];
            const Vec3& outward = grid.outward(hit.triangle);
            const double depth = (x - p0).dot(outward);  // beyond its triangle's plane
            if (!(depth > 0.0)) continue;
            ++stats.nodesInContact;
            NodeContact nc;
            nc.node = i;
            nc.depth = depth;
            nc.normal = -outward;
            nc.point = x + 0.5 * depth * nc.normal;
            nc.area = a.nodes.areas[i];
            contacts.push_back(nc);
            hits.push_back(hit);
        }
    };
    auto isClear = [&](const NodeBlock& run) {
        return !grid.mayTouch(rotation * run.center + grain.pose.position, run.radius);
    };
    forEachBlockNotClear(a, isClear, visit, stats);
    if (contacts.empty()) return;

    // The membrane under the grain: the mean velocity of the points its nodes met.
    ContactGrain membraneView;
    Vec3 velocity = Vec3::Zero();
    for (const MembraneHit& h : hits) {
        const auto& v = m.triangles[size_t(h.triangle)].vertices;
        for (int k = 0; k < 3; ++k) velocity += h.weights[k] * m.velocities[size_t(v[k])];
    }
    membraneView.velocity = velocity / static_cast<double>(hits.size());
    membraneView.pose.position = grain.pose.position;
    membraneView.index = -1;
    membraneView.mass = 0.0;

    ContactModel frictionless = model;
    frictionless.friction = 0.0;
    ContactSide side;
    side.tester = &grain;
    side.other = &membraneView;
    side.contacts.swap(contacts);
    std::vector<PointForce>& forces = out.pointForces;
    forces.clear();
    out.result = resolveContact(&side, 1, frictionless, dt, &forces, &scratch);

    // Each node's force, reversed, to its triangle's vertices; the dashpot's (node −1) in
    // proportion to the nodes' elastic forces.
    double elasticSum = 0.0;
    for (const PointForce& f : forces)
        if (f.node >= 0) elasticSum += f.force.norm();
    Vec3 dashpot = Vec3::Zero();
    for (const PointForce& f : forces)
        if (f.node < 0) dashpot += f.force;
    size_t k = 0;
    for (const PointForce& f : forces) {
        if (f.node < 0) continue;
        while (k < side.contacts.size() && side.contacts[k].node != f.node) ++k;
        if (k == side.contacts.size()) break;  // (cannot happen: forces follow the contacts)
        const MembraneHit& h = hits[k];
        const Vec3 onMembrane =
            -(f.force + (elasticSum > 0.0 ? f.force.norm() / elasticSum : 0.0) * dashpot);
        const auto& v = m.triangles[size_t(h.triangle)].vertices;
        for (int c = 0; c < 3; ++c) {
            if (h.weights[c] == 0.0) continue;
            out.reactions.emplace_back(v[c], h.weights[c] * onMembrane);
            out.stiffness.emplace_back(v[c], h.weights[c] * f.stiffness);
        }
    }
    side.contacts.swap(contacts);
}

} // namespace lsdem
