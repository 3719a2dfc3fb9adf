// Grains against a membrane (MembraneContact.h): the triangles binned in a grid, each node
// against the triangles of its cell, the law on the nodes found, and their forces handed to
// the triangles' vertices.
#include "lsdem/simulation/MembraneContact.h"

#include "lsdem/contact/NodeBlockWalk.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

std::int64_t MembraneTriangleGrid::keyOf(long long i, long long j, long long k) const
{
    // 21 bits a direction: 2 million cells across, far beyond a membrane's extent in cells.
    constexpr long long kBias = 1 << 20;
    return ((i + kBias) << 42) | ((j + kBias) << 21) | (k + kBias);
}

std::int64_t MembraneTriangleGrid::cellOf(const Vec3& x) const
{
    if (mKeys.empty() || (x.array() < mLow.array()).any() || (x.array() > mHigh.array()).any())
        return -1;
    return keyOf(static_cast<long long>(std::floor((x.x() - mLow.x()) / mCell)),
                 static_cast<long long>(std::floor((x.y() - mLow.y()) / mCell)),
                 static_cast<long long>(std::floor((x.z() - mLow.z()) / mCell)));
}

const std::vector<int>& MembraneTriangleGrid::inCell(std::int64_t key) const
{
    if (key < 0) return mNone;
    const auto found = std::lower_bound(mKeys.begin(), mKeys.end(), key);
    if (found == mKeys.end() || *found != key) return mNone;
    return mTriangles[size_t(found - mKeys.begin())];
}

void MembraneTriangleGrid::build(const Membrane& m, double reach)
{
    mReach = reach;
    mKeys.clear();
    mTriangles.clear();
    if (m.triangles.empty()) return;
    // Cells as wide as the mean grown triangle box: a triangle lies in a few, a cell holds
    // a few dozen (the largest box would make every cell hold all of a stretched membrane's).
    mLow = Vec3::Constant(std::numeric_limits<double>::infinity());
    mHigh = -mLow;
    std::vector<std::pair<Vec3, Vec3>>& boxes = mBoxes;
    boxes.clear();
    boxes.reserve(m.triangles.size());
    double extent = 0.0;
    for (const MembraneTriangle& t : m.triangles) {
        Vec3 low = m.positions[size_t(t.vertices[0])], high = low;
        for (int v : t.vertices) {
            low = low.cwiseMin(m.positions[size_t(v)]);
            high = high.cwiseMax(m.positions[size_t(v)]);
        }
        low.array() -= reach;
        high.array() += reach;
        extent += (high - low).maxCoeff();
        mLow = mLow.cwiseMin(low);
        mHigh = mHigh.cwiseMax(high);
        boxes.emplace_back(low, high);
    }
    mCell = extent / static_cast<double>(boxes.size());
    std::vector<std::pair<std::int64_t, int>> binned;
    for (size_t t = 0; t < boxes.size(); ++t) {
        const Vec3 low = ((boxes[t].first - mLow) / mCell).array().floor();
        const Vec3 high = ((boxes[t].second - mLow) / mCell).array().floor();
        for (long long i = (long long)low.x(); i <= (long long)high.x(); ++i)
            for (long long j = (long long)low.y(); j <= (long long)high.y(); ++j)
                for (long long k = (long long)low.z(); k <= (long long)high.z(); ++k)
                    binned.emplace_back(keyOf(i, j, k), static_cast<int>(t));
    }
    std::sort(binned.begin(), binned.end());
    for (const auto& [key, triangle] : binned) {
        if (mKeys.empty() || mKeys.back() != key) {
            mKeys.push_back(key);
            mTriangles.emplace_back();
        }
        mTriangles.back().push_back(triangle);
    }
}

bool MembraneTriangleGrid::mayTouch(const Vec3& c, double r) const
{
    if (mKeys.empty()) return false;
    if ((c.array() + r < mLow.array()).any() || (c.array() - r > mHigh.array()).any())
        return false;
    const Vec3 low = ((c.array() - r - mLow.array()) / mCell).floor();
    const Vec3 high = ((c.array() + r - mLow.array()) / mCell).floor();
    for (long long i = (long long)low.x(); i <= (long long)high.x(); ++i)
        for (long long j = (long long)low.y(); j <= (long long)high.y(); ++j)
            for (long long k = (long long)low.z(); k <= (long long)high.z(); ++k)
                if (std::binary_search(mKeys.begin(), mKeys.end(), keyOf(i, j, k))) return true;
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
    std::int64_t lastCell = -1;
    const std::vector<int>* lastNear = &grid.inCell(-1);
    auto visit = [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            const Vec3 x = rotation * a.nodes.positions[i] + grain.pose.position;
            const std::int64_t cell = grid.cellOf(x);
            if (cell != lastCell) {
                lastCell = cell;
                lastNear = &grid.inCell(cell);
            }
            const std::vector<int>& near = *lastNear;
            if (near.empty()) continue;
            ++stats.nodesSampled;
            // The nearest triangle, ties to the lower index (the same on any thread count).
            double best = std::numeric_limits<double>::infinity();
            MembraneHit hit;
            for (int t : near) {
                if (!grid.holds(t, x)) continue;
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
            const auto& v = m.triangles[size_t(hit.triangle)].vertices;
            const Vec3 &p0 = m.positions[size_t(v[0])], &p1 = m.positions[size_t(v[1])],
                       &p2 = m.positions[size_t(v[2])];
            const Vec3 outward = (p1 - p0).cross(p2 - p0).normalized();
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
