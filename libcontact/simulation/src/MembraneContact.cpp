// Grains against a membrane (MembraneContact.h): the triangles binned in a grid, each grain's
// list of the triangles near it, each node against those near its block, the law on the nodes
// found, and their forces handed to the triangles' vertices.
#include "lsdem/simulation/MembraneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"
#include "lsdem/core/Error.h"

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
/// A grain's skin over the reach: its candidate nodes last until one of its nodes has moved
/// this far (wider keeps them longer but lists more nodes to check each step).
constexpr double kGrainSkinOverReach = 0.25;
} // namespace

void MembraneTriangleGrid::update(const Membrane& m, double reach)
{
    // (A membrane's triangles keep their vertices through a run: their count tells a new one.)
    bool stale = reach != mReach || m.positions.size() != mBinnedAt.size() ||
                 m.triangles.size() != mBinnedTriangles;
    // One pass over the vertices: a vertex gone to NaN or infinity would make the cells' size
    // meaningless (say so); and a box grown by reach + skin when binned still holds every point
    // within reach of its triangle while no vertex has moved more than the skin (a distance,
    // so that the grains' candidate nodes can count on it too).
    const double skin = kSkinOverReach * reach;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        if (!m.positions[i].allFinite())
            throw Error("membrane '" + m.name + "'",
                        "vertex " + std::to_string(i) + " is no longer at a finite position",
                        "its step is too large for its rubber or its contacts: lower "
                        "[simulation] time_step, or raise its density (mass scaling)");
        stale = stale || !((m.positions[i] - mBinnedAt[i]).squaredNorm() <= skin * skin);
    }
    // The faces every time: the contact's depth is measured along their normals.
    mFaces.resize(m.triangles.size());
    for (size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& v = m.triangles[t].vertices;
        MembraneFace& f = mFaces[t];
        f.p0 = m.positions[size_t(v[0])];
        f.p1 = m.positions[size_t(v[1])];
        f.p2 = m.positions[size_t(v[2])];
        const Vec3 e1 = f.p1 - f.p0, e2 = f.p2 - f.p0, cross = e1.cross(e2);
        f.outward = cross.normalized();
        f.flat = cross.norm() >= 1e-6 * e1.norm() * e2.norm();
        f.centroid = (f.p0 + f.p1 + f.p2) / 3.0;
        f.spread = std::sqrt(std::max({(f.p0 - f.centroid).squaredNorm(),
                                       (f.p1 - f.centroid).squaredNorm(),
                                       (f.p2 - f.centroid).squaredNorm()}));
    }
    if (stale) {
        mReach = reach;
        bin(m);
    }
}

double MembraneTriangleGrid::skin() const { return kSkinOverReach * mReach; }

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

void MembraneTriangleGrid::listNear(const Vec3& c, double r, std::vector<int>& out) const
{
    if (mEntries.empty()) return;
    long long from[3], to[3];
    for (int a = 0; a < 3; ++a)
        if (!cellRange(a, c[a] - r, c[a] + r, from[a], to[a])) return;
    const size_t first = out.size();
    for (long long i = from[0]; i <= to[0]; ++i)
        for (long long j = from[1]; j <= to[1]; ++j)
            for (long long k = from[2]; k <= to[2]; ++k) {
                const size_t cell = size_t((i * mCells[1] + j) * mCells[2] + k);
                for (uint32_t e = mCellStart[cell]; e < mCellStart[cell + 1]; ++e) {
                    const Entry& box = mEntries[e];
                    bool meets = true;
                    for (int a = 0; a < 3; ++a)
                        meets = meets && c[a] + r >= double(box.low[a]) &&
                                c[a] - r <= double(box.high[a]);
                    if (meets) out.push_back(box.triangle);
                }
            }
    std::sort(out.begin() + std::ptrdiff_t(first), out.end());
    out.erase(std::unique(out.begin() + std::ptrdiff_t(first), out.end()), out.end());
}

namespace {

/// A length's rounding margin next to coordinates of size @a scale: culls use it so that a
/// node placed with rounding is never passed over.
double roundingMargin(double length, double scale) { return 1e-9 * (length + scale); }

/// Face @a f's box (triangle @a t) grown by @a grow.
MembraneTriangleBox triangleBox(const MembraneFace& f, int t, double grow)
{
    MembraneTriangleBox box;
    box.triangle = t;
    box.low = f.p0.cwiseMin(f.p1).cwiseMin(f.p2);
    box.high = f.p0.cwiseMax(f.p1).cwiseMax(f.p2);
    const double g =
        grow + roundingMargin(grow, box.low.cwiseAbs().cwiseMax(box.high.cwiseAbs()).maxCoeff());
    box.low.array() -= g;
    box.high.array() += g;
    return box;
}

/// A lower bound of the distance from @a x to face @a n: the larger of its distances from its
/// plane (if its normal is true) and from its centroid's sphere, less @a slack for rounding.
double distanceBound(const Vec3& x, const MembraneFace& n, double slack)
{
    const double fromSphere = (x - n.centroid).norm() - n.spread;
    return (n.flat ? std::max(std::abs((x - n.p0).dot(n.outward)), fromSphere) : fromSphere) -
           slack;
}

/// How far a node of a grain of bounding radius @a radius may have moved since the pose
/// (@a c0, @a q0), now at (@a c, @a q): its centre's move and the chord of its turn.
double largestNodeMove(const Vec3& c0, const Quat& q0, const Vec3& c, const Quat& q, double radius)
{
    const Quat turn = q * q0.conjugate();  // (|its vector part| is sin of half the angle)
    return (c - c0).norm() + 2.0 * turn.vec().norm() * radius;
}

/// Search @a grain's nodes for those that may come within the reach of the membrane while
/// it and the grain move less than their skins: every node with a triangle within
/// @a searchReach, with those triangles (in @a out's candidate lists).
void searchCandidates(const ContactGrain& grain, const MembraneTriangleGrid& grid, double searchReach,
                      MembraneGrainContact& out)
{
    const GrainAsset& a = *grain.asset;
    const Vec3& centre = grain.pose.position;
    ++out.searches;
    out.searchedAt = centre;
    out.searchedOrientation = grain.pose.orientation;
    out.searchedAsset = grain.asset;
    out.searchedBinning = grid.binnings();
    out.candidateNodes.clear();
    out.candidateStart.assign(1, 0);
    out.candidateTriangles.clear();
    // The triangles whose box as binned meets the grain's sphere grown by what the search adds
    // to the grid's reach (a triangle within searchReach of a node lies within the reach of a
    // point that far from it: its box holds that point).
    std::vector<int>& listed = out.listed;
    listed.clear();
    grid.listNear(centre, a.boundingRadius + (searchReach - grid.reach()), listed);
    std::vector<MembraneTriangleBox>& near = out.near;
    near.clear();
    const double sphereRadius =
        a.boundingRadius + roundingMargin(a.boundingRadius, centre.cwiseAbs().maxCoeff());
    for (const int t : listed) {
        const MembraneTriangleBox box = triangleBox(grid.face(t), t, searchReach);
        if (box.meets(centre, sphereRadius)) near.push_back(box);
    }
    if (near.empty()) return;
    const Eigen::Matrix3d rotation = grain.pose.orientation.toRotationMatrix();
    std::vector<int>& nearCluster = out.nearCluster;
    std::vector<int>& nearBlock = out.nearBlock;
    // Of the triangles @a from (indices into near), those whose box meets the run's sphere.
    auto nearRun = [&](const NodeBlock& run, const std::vector<int>& from, std::vector<int>& to) {
        const Vec3 c = rotation * run.center + centre;
        const double r = run.radius + roundingMargin(run.radius, c.cwiseAbs().maxCoeff());
        to.clear();
        for (const int k : from)
            if (near[size_t(k)].meets(c, r)) to.push_back(k);
        return !to.empty();
    };
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[size_t(i)] + centre;
            const double slack = roundingMargin(searchReach, x.cwiseAbs().maxCoeff());
            const size_t before = out.candidateTriangles.size();
            for (const int k : nearBlock) {
                const MembraneTriangleBox& box = near[size_t(k)];
                if (box.holds(x) && distanceBound(x, grid.face(box.triangle), slack) <= searchReach)
                    out.candidateTriangles.push_back(box.triangle);
            }
            if (out.candidateTriangles.size() == before) continue;
            out.candidateNodes.push_back(i);
            out.candidateStart.push_back(int(out.candidateTriangles.size()));
        }
    };
    // Clusters against every triangle near the grain, their blocks against the cluster's (a
    // grain without blocks is visited whole, against all of them).
    std::vector<int> allNear(near.size());
    for (size_t k = 0; k < near.size(); ++k) allNear[k] = int(k);
    nearBlock = allNear;
    const auto isClusterClear = [&](const NodeBlock& cluster) {
        return !nearRun(cluster, allNear, nearCluster);
    };
    const auto isBlockClear = [&](const NodeBlock& block) {
        return !nearRun(block, nearCluster, nearBlock);
    };
    NodeCheckStats unused;  // (the evaluation counts the nodes)
    forEachBlockNotClear(a, isClusterClear, isBlockClear, visit, unused);
}

} // namespace

void computeMembraneContact(const ContactGrain& grain, const Membrane& m,
                            const MembraneTriangleGrid& grid, const ContactModel& model,
                            double dt, MembraneGrainContact& out, ContactScratch& scratch)
{
    out.result = PairForces();
    out.stats = NodeCheckStats();
    NodeCheckStats& stats = out.stats;
    out.reactions.clear();
    out.loads.clear();
    out.grainShare = 1.0;
    const GrainAsset& a = *grain.asset;
    const long long count = static_cast<long long>(a.nodes.size());
    stats.nodesConsidered += count;
    const double reach = grid.reach();
    // The candidate nodes hold while the grain's nodes have moved less than its skin and the
    // membrane's vertices less than twice the grid's (each within the grid's skin of where
    // they were binned): a node within reach now was within reach + both skins then.
    const double grainSkin = kGrainSkinOverReach * reach;
    if (out.searchedBinning != grid.binnings() || out.searchedAsset != grain.asset ||
        !(largestNodeMove(out.searchedAt, out.searchedOrientation, grain.pose.position,
                          grain.pose.orientation, a.boundingRadius) <= grainSkin))
        searchCandidates(grain, grid, reach + grainSkin + 2.0 * grid.skin(), out);
    if (out.candidateNodes.empty()) {
        stats.nodesCulled += count;
        return;
    }
    std::vector<NodeContact>& contacts = scratch.contacts[0];
    contacts.clear();
    std::vector<MembraneHit>& hits = out.hits;
    hits.clear();
    const Eigen::Matrix3d rotation = grain.pose.orientation.toRotationMatrix();
    const Vec3& centre = grain.pose.position;
    std::vector<std::pair<int, double>>& nearNode = out.nearNode;
    stats.nodesCulled += count - static_cast<long long>(out.candidateNodes.size());
    for (size_t c = 0; c < out.candidateNodes.size(); ++c) {
        const int i = out.candidateNodes[c];
        const Vec3 x = rotation * a.nodes.positions[size_t(i)] + centre;
        ++stats.nodesSampled;
        // A node inside the plane of each of its triangles has depth ≤ 0 at whichever is
        // nearest: passed over. Else its triangles, each with a lower bound of its distance,
        // those within reach kept.
        const int* from = out.candidateTriangles.data() + out.candidateStart[c];
        const int* to = out.candidateTriangles.data() + out.candidateStart[c + 1];
        bool outside = false;
        for (const int* t = from; t != to && !outside; ++t) {
            const MembraneFace& f = grid.face(*t);
            outside = (x - f.p0).dot(f.outward) > 0.0;
        }
        if (!outside) continue;
        const double slack = roundingMargin(reach, x.cwiseAbs().maxCoeff());
        nearNode.clear();
        for (const int* t = from; t != to; ++t) {
            const double bound = distanceBound(x, grid.face(*t), slack);
            if (bound <= reach) nearNode.emplace_back(*t, bound);
        }
        if (nearNode.empty()) continue;
        // The nearest triangle, ties to the lower index (the same on any thread count): the
        // one of least bound first, then only those whose bound does not exceed the nearest
        // so far (a triangle passed over is farther than it).
        double best = std::numeric_limits<double>::infinity();
        MembraneHit hit;
        const auto measure = [&](int t) {
            const MembraneFace& n = grid.face(t);
            const Vec3 w = nearestWeights(x, n.p0, n.p1, n.p2);
            const double distance = (x - (w[0] * n.p0 + w[1] * n.p1 + w[2] * n.p2)).squaredNorm();
            if (distance < best || (distance == best && t < hit.triangle)) {
                best = distance;
                hit.triangle = t;
                hit.weights = w;
            }
        };
        size_t first = 0;
        for (size_t k = 1; k < nearNode.size(); ++k)
            if (nearNode[k].second < nearNode[first].second) first = k;
        measure(nearNode[first].first);
        for (size_t k = 0; k < nearNode.size(); ++k) {
            const double bound = nearNode[k].second;
            if (k != first && (bound <= 0.0 || bound * bound <= best)) measure(nearNode[k].first);
        }
        if (!(best <= reach * reach)) continue;
        const MembraneFace& nearest = grid.face(hit.triangle);
        const double depth = (x - nearest.p0).dot(nearest.outward);  // beyond its plane
        if (!(depth > 0.0)) continue;
        ++stats.nodesInContact;
        NodeContact nc;
        nc.node = i;
        nc.depth = depth;
        nc.normal = -nearest.outward;
        nc.point = x + 0.5 * depth * nc.normal;
        nc.area = a.nodes.areas[size_t(i)];
        contacts.push_back(nc);
        hits.push_back(hit);
    }
    if (contacts.empty()) return;

    // The membrane under the grain (MembraneGrainContact): each vertex's weight b_v, the mean
    // velocity they give, and the mass that mean moves with.
    std::vector<std::pair<int, double>>& patch = out.patchWeights;
    patch.clear();
    const double perHit = 1.0 / static_cast<double>(hits.size());
    for (const MembraneHit& h : hits) {
        const auto& v = m.triangles[size_t(h.triangle)].vertices;
        for (int k = 0; k < 3; ++k)
            if (h.weights[k] != 0.0) patch.emplace_back(v[k], perHit * h.weights[k]);
    }
    std::sort(patch.begin(), patch.end());  // (then summed in vertex order: any thread count)
    size_t kept = 0;
    for (size_t k = 0; k < patch.size(); ++k) {
        if (kept > 0 && patch[kept - 1].first == patch[k].first)
            patch[kept - 1].second += patch[k].second;
        else
            patch[kept++] = patch[k];
    }
    patch.resize(kept);
    const auto isFree = [&](int vertex) { return m.heldBy[size_t(vertex)] < 0; };
    ContactGrain membraneView;
    Vec3 velocity = Vec3::Zero();
    double inverseMass = 0.0;
    for (const auto& [vertex, b] : patch) {
        velocity += b * m.velocities[size_t(vertex)];
        if (isFree(vertex)) inverseMass += b * b / m.masses[size_t(vertex)];
    }
    membraneView.velocity = velocity;
    membraneView.pose.position = grain.pose.position;
    membraneView.index = -1;
    membraneView.mass = inverseMass > 0.0 ? 1.0 / inverseMass : 0.0;  // 0: held, immovable
    double vertexShare = 1.0;
    if (membraneView.mass > 0.0 && grain.mass > 0.0) {
        out.grainShare = 1.0 + grain.mass / membraneView.mass;
        vertexShare = 1.0 + membraneView.mass / grain.mass;
    }

    ContactModel frictionless = model;
    frictionless.friction = 0.0;
    ContactSide side;
    side.tester = &grain;
    side.other = &membraneView;
    side.contacts.swap(contacts);
    std::vector<PointForce>& forces = out.pointForces;
    forces.clear();
    out.result = resolveContact(&side, 1, frictionless, dt, &forces, &scratch);

    // Each node's force, reversed, to its triangle's vertices; the dashpot's (node −1) by the
    // weights b_v its velocity was read with.
    size_t k = 0;
    for (const PointForce& f : forces) {
        if (f.node < 0) {
            for (const auto& [vertex, b] : patch) out.reactions.emplace_back(vertex, -b * f.force);
            continue;
        }
        while (k < side.contacts.size() && side.contacts[k].node != f.node) ++k;
        if (k == side.contacts.size()) break;  // (cannot happen: forces follow the contacts)
        const MembraneHit& h = hits[k];
        const auto& v = m.triangles[size_t(h.triangle)].vertices;
        for (int c = 0; c < 3; ++c) {
            if (h.weights[c] == 0.0) continue;
            out.reactions.emplace_back(v[c], -h.weights[c] * f.force);
            if (isFree(v[c]))
                out.loads.push_back({v[c], vertexShare * h.weights[c] * f.stiffness, 0.0});
        }
    }
    if (out.result.dashpot > 0.0)
        for (const auto& [vertex, b] : patch)
            if (isFree(vertex))
                out.loads.push_back({vertex, 0.0, vertexShare * b * out.result.dashpot});
    side.contacts.swap(contacts);
}

} // namespace lsdem
