/// @file MembraneContact.h
/// @brief Grains against a membrane (Membrane.h): a grain's nodes that have passed through
///        the membrane's triangles to its outer side, found as its nodes inside a wall are, and
///        turned into forces by the same contact law; each node's force goes back to the three
///        vertices of the triangle it met, by barycentric weights, so the grain and the
///        membrane exchange equal and opposite forces.
///
/// The contact is frictionless (the law's normal force and its dashpot; μ is not used): lab
/// membranes are lubricated or not, and a shear spring would need a history per node and
/// triangle; both are to come.
#pragma once

#include "lsdem/contact/ContactLaw.h"
#include "lsdem/simulation/Membrane.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace lsdem {

/// A membrane triangle as it is now: its vertices, its unit outward normal
/// ((p1 − p0) × (p2 − p0) normalized; zero if degenerate), and the sphere about its centroid
/// that holds it.
struct MembraneFace
{
    Vec3 p0, p1, p2, outward, centroid;
    double spread = 0.0;  ///< the centroid's distance to the farthest vertex
    /// Whether the normal is true to the plane (the edges' cross product is not lost in
    /// rounding), so that a distance from the plane bounds one from the triangle.
    bool flat = false;
};

/// The membrane's triangles binned in a uniform grid of cells, so a grain finds the triangles
/// near it from the cells its bounding sphere overlaps. Each triangle is binned in every cell
/// that its box, grown by the reach and a skin, overlaps; the binning is kept until a vertex
/// has moved more than the skin since (a membrane moves little in a step, and rebinning is a
/// sort), so between binnings the grown boxes still hold every point within the reach of their
/// triangles as they are now. The cells lie in a dense array over the boxes' union, each
/// holding copies of its triangles' boxes side by side.
class MembraneTriangleGrid
{
public:
    /// A triangle as binned in a cell: its box grown by the reach and the skin when binned
    /// (rounded outward to float), and its index.
    struct Entry
    {
        float low[3], high[3];
        int triangle;
    };

    /// Bring the grid up to @a m as it is now: its triangles' faces always, and its
    /// binning when none was made for a reach of @a reach (> 0, length; a node that far outside
    /// the membrane has escaped and is not pushed back), when its vertices or triangles changed
    /// in number, or when a vertex has moved more than the skin (a quarter of the reach) since.
    void update(const Membrane& m, double reach);
    /// Append to @a out, sorted and once each, every triangle whose grown box as binned
    /// overlaps the axis-aligned box of the sphere (@a c, @a r): among them every triangle
    /// within the reach of a point of the sphere, until the next binning.
    void listNear(const Vec3& c, double r, std::vector<int>& out) const;
    /// Triangle @a t as it is now.
    const MembraneFace& face(int t) const { return mFaces[size_t(t)]; }
    double reach() const { return mReach; }
    /// How far a vertex may move from where it was binned before the grid bins anew.
    double skin() const;
    /// How many times the triangles were binned (a grain's list of them lasts until the next).
    long long binnings() const { return mBinnings; }

private:
    void bin(const Membrane& m);
    /// The range of cells along axis @a a that [lo, hi] overlaps (false: none).
    bool cellRange(int a, double lo, double hi, long long& from, long long& to) const;

    double mReach = 0.0, mCell = 0.0, mInverseCell = 0.0;
    Vec3 mLow = Vec3::Zero();        ///< the first cell's lowest corner
    long long mCells[3] = {0, 0, 0};  ///< cells along x, y, z
    std::vector<std::uint32_t> mCellStart;  ///< per cell (x-major), then one past the last
    std::vector<Entry> mEntries;            ///< by cell
    std::vector<Vec3> mBinnedAt;            ///< the vertices' positions when binned
    size_t mBinnedTriangles = 0;
    std::vector<MembraneFace> mFaces;       ///< per triangle, now
    long long mBinnings = 0;
};

/// A triangle's box grown by a reach (with a rounding margin), in a search near a grain.
struct MembraneTriangleBox
{
    Vec3 low, high;
    int triangle = -1;
    bool holds(const Vec3& x) const
    {
        return (x.array() >= low.array()).all() && (x.array() <= high.array()).all();
    }
    /// Whether the box meets the sphere (@a c, @a r).
    bool meets(const Vec3& c, double r) const
    {
        const Eigen::Array3d gap =
            (low.array() - c.array()).max(c.array() - high.array()).max(0.0);
        return gap.matrix().squaredNorm() <= r * r;
    }
};

/// Where a grain's node met the membrane: its triangle and the barycentric weights there.
struct MembraneHit
{
    int triangle = -1;
    Vec3 weights = Vec3::Zero();  ///< of the triangle's vertices, summing to 1
};

/// What a vertex bears of one grain's contact, for the membrane's stable step: its springs
/// Σ w·k over the nodes that met its triangles (w the vertex's barycentric weight there) and
/// its part b·c of the contact's dashpot c (b its weight in the velocity the dashpot reads),
/// both times the vertex's share of the pair, 1 + m_m/M (MembraneGrainContact).
struct MembraneVertexLoad
{
    int vertex = -1;
    double stiffness = 0.0;  ///< force/length
    double damping = 0.0;    ///< force·time/length
};

/// One grain's contact with a membrane at this evaluation.
///
/// The membrane under the grain moves at the mean velocity of the points the grain's nodes met,
/// Σ b_v·u_v (b_v: each vertex's barycentric weights summed over those points, over their
/// number), and the dashpot reads the grain's velocity against it. Its reaction goes back to
/// the vertices by the same weights b_v, so it only ever dissipates: its power on grain and
/// membrane together is the dashpot's force times their relative speed. The mean moves as a
/// body of mass m_m = 1/Σ b_v²/m_v under that reaction (held vertices count as immovable), and
/// the dashpot is calibrated on the pair's reduced mass with it, as between two grains: a heavy
/// grain on a light membrane gets the dashpot that the membrane can bear.
///
/// The stable step of the pair: each contact node pushes the grain and its triangle's vertices
/// apart, and (a + b)² ≤ (1 + s)·a² + (1 + 1/s)·b² splits that spring (and the dashpot) into one
/// on the grain alone, (1 + s) times as stiff, and springs on the vertices alone, (1 + 1/s)
/// times (by Cauchy–Schwarz, Σ w = 1: a spring on the weighted mean is at most the weighted
/// springs on each vertex). The grains' check and the membrane's then bound the whole system's
/// fastest mode between them. s = M/m_m (M the grain's mass) is exact for two bodies on one
/// spring, as the share 1 + m_i/m_j between two grains (SimulationForces.cpp).
struct MembraneGrainContact
{
    PairForces result;  ///< on first: the grain; on second: the membrane as a whole
    /// The reaction on each vertex it touched, (vertex, force), in the order found.
    std::vector<std::pair<int, Vec3>> reactions;
    /// What each free vertex it touched bears, for the membrane's step (once per node and
    /// vertex, in the order found).
    std::vector<MembraneVertexLoad> loads;
    /// 1 + M/m_m: how much stiffer the grain's check counts its springs and dashpot on the
    /// membrane than on a wall (1 on held vertices). The vertices' 1 + m_m/M is in @ref loads.
    double grainShare = 1.0;
    NodeCheckStats stats;  ///< of this evaluation's node checks
    // Working memory, kept from step to step: where each node met the membrane, and the
    // point forces on the grain as the law gave them.
    std::vector<MembraneHit> hits;
    std::vector<PointForce> pointForces;
    std::vector<std::pair<int, double>> patchWeights;  ///< (vertex, b_v), by vertex
    // The grain's candidate nodes, from a search of its nodes kept while it holds (until the
    // grain has moved more than its skin, the grid rebins, or the grain's asset changes): each
    // node that may come within reach meanwhile, in node order, with the triangles it may meet
    // (candidateTriangles[candidateStart[c] .. candidateStart[c + 1])). They belong to one
    // grid: pass each grid its own MembraneGrainContact objects.
    std::vector<int> candidateNodes, candidateStart, candidateTriangles;
    Vec3 searchedAt = Vec3::Zero();         ///< the grain's pose at the search
    Quat searchedOrientation = Quat::Identity();
    const GrainAsset* searchedAsset = nullptr;
    long long searchedBinning = -1;         ///< the grid's binning at the search
    long long searches = 0;                 ///< how many searches were made (for tests)
    // Working memory: in a search, the triangles listed and near the grain, and a cluster's
    // and a block's of those (indices into near); a node's (triangle, bound of its distance).
    std::vector<int> listed;
    std::vector<MembraneTriangleBox> near;
    std::vector<int> nearCluster, nearBlock;
    std::vector<std::pair<int, double>> nearNode;
};

/// The contact of @a grain (seen by the law) with membrane @a m, whose triangles are binned
/// in @a grid (updated for @a m as it is now), under @a model (μ ignored): the nodes outside
/// it within the grid's reach, depth their distance from the plane of the nearest triangle,
/// normal that triangle's inward one. Only the grain's candidate nodes are looked at: those
/// that a search found within the reach and the skins of the grain and the membrane, kept in
/// @a out from call to call until one of them has moved more than its skin.
/// The membrane's motion, dashpot and shares under the grain: MembraneGrainContact.
/// @param dt the step (for the dashpot's dissipation; no shear is carried)
void computeMembraneContact(const ContactGrain& grain, const Membrane& m,
                            const MembraneTriangleGrid& grid, const ContactModel& model,
                            double dt, MembraneGrainContact& out, ContactScratch& scratch);

} // namespace lsdem
