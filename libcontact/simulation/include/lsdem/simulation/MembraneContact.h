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
#include <vector>

namespace lsdem {

/// The membrane's triangles binned in a uniform grid of cells, so a node finds the triangles
/// near it in its own cell. Each triangle is binned in every cell that its box, grown by the
/// reach and a skin, overlaps; the binning is kept until a vertex has moved more than the skin
/// since (a membrane moves little in a step, and rebinning is a sort), so between binnings the
/// grown boxes still hold every point within the reach of their triangles as they are now.
/// The cells lie in a dense array over the boxes' union (one look-up finds a node's cell), each
/// holding copies of its triangles' boxes side by side (a node tests them without reaching
/// into other memory).
///
/// Only a node outside a triangle's plane can touch it, so each step a cell is marked live
/// when some point of it lies outside the plane of one of its triangles; nodes in other cells
/// (most of those near the membrane: it is pressed onto the grains from outside) are passed
/// over, and so are the blocks of nodes that overlap no live cell.
class MembraneTriangleGrid
{
public:
    /// A triangle as binned in a cell: its box grown by the reach and the skin when binned
    /// (rounded outward to float), and its index.
    struct Entry
    {
        float low[3], high[3];
        int triangle;
        bool holds(const Vec3& x) const
        {
            return x.x() >= double(low[0]) && x.x() <= double(high[0]) &&
                   x.y() >= double(low[1]) && x.y() <= double(high[1]) &&
                   x.z() >= double(low[2]) && x.z() <= double(high[2]);
        }
    };

    /// Bring the grid up to @a m as it is now: its triangles' outward normals always, and its
    /// binning when none was made for a reach of @a reach (> 0, length; a node that far outside
    /// the membrane has escaped and is not pushed back), when its vertices or triangles changed
    /// in number, or when a vertex has moved more than the skin (a quarter of the
    /// reach) since; and which cells are live.
    void update(const Membrane& m, double reach);
    /// The cell of @a x (-1 outside every grown box, or in a cell not live now).
    std::int64_t cellOf(const Vec3& x) const;
    /// The triangles binned in cell @a cell (from cellOf): those whose grown box may hold a
    /// point in it, each with that box (Entry::holds tells).
    const Entry* cellBegin(std::int64_t cell) const
    {
        return cell < 0 ? nullptr : mEntries.data() + mCellStart[size_t(cell)];
    }
    const Entry* cellEnd(std::int64_t cell) const
    {
        return cell < 0 ? nullptr : mEntries.data() + mCellStart[size_t(cell) + 1];
    }
    /// Whether a sphere (centre @a c, radius @a r) overlaps a live cell.
    bool mayTouch(const Vec3& c, double r) const;
    /// Triangle @a t's unit outward normal now, as (p1 − p0) × (p2 − p0) normalized.
    const Vec3& outward(int t) const { return mOutward[size_t(t)]; }
    double reach() const { return mReach; }
    /// How many times the triangles were binned (for tests and reports).
    long long binnings() const { return mBinnings; }

private:
    void bin(const Membrane& m);
    /// Mark the cells live now (mLive), from the triangles' planes now.
    void markLiveCells(const Membrane& m);
    /// The range of cells along axis @a a that [lo, hi] overlaps (false: none).
    bool cellRange(int a, double lo, double hi, long long& from, long long& to) const;

    double mReach = 0.0, mCell = 0.0, mInverseCell = 0.0;
    Vec3 mLow = Vec3::Zero();        ///< the first cell's lowest corner
    long long mCells[3] = {0, 0, 0};  ///< cells along x, y, z
    std::vector<std::uint32_t> mCellStart;  ///< per cell (x-major), then one past the last
    std::vector<Entry> mEntries;            ///< by cell
    std::vector<std::uint8_t> mLive;        ///< per cell: 1 if live now
    std::vector<Vec3> mBinnedAt;            ///< the vertices' positions when binned
    size_t mBinnedTriangles = 0;
    std::vector<Vec3> mOutward;             ///< per triangle, now
    long long mBinnings = 0;
};

/// Where a grain's node met the membrane: its triangle and the barycentric weights there.
struct MembraneHit
{
    int triangle = -1;
    Vec3 weights = Vec3::Zero();  ///< of the triangle's vertices, summing to 1
};

/// One grain's contact with a membrane at this evaluation.
struct MembraneGrainContact
{
    PairForces result;  ///< on first: the grain; on second: the membrane as a whole
    /// The reaction on each vertex it touched, (vertex, force), in the order found.
    std::vector<std::pair<int, Vec3>> reactions;
    /// Σ (barycentric weight × node stiffness) per vertex touched, for the membrane's step.
    std::vector<std::pair<int, double>> stiffness;
    NodeCheckStats stats;  ///< of this evaluation's node checks
    // Working memory, kept from step to step: where each node met the membrane, and the
    // point forces on the grain as the law gave them.
    std::vector<MembraneHit> hits;
    std::vector<PointForce> pointForces;
};

/// The contact of @a grain (seen by the law) with membrane @a m, whose triangles are binned
/// in @a grid (updated for @a m as it is now), under @a model (μ ignored): the nodes outside
/// it within the grid's reach, depth their distance from the plane of the nearest triangle,
/// normal that triangle's inward one.
/// The membrane moves under the grain at the mean velocity of the points its nodes met.
/// @param dt the step (for the dashpot's dissipation; no shear is carried)
void computeMembraneContact(const ContactGrain& grain, const Membrane& m,
                            const MembraneTriangleGrid& grid, const ContactModel& model,
                            double dt, MembraneGrainContact& out, ContactScratch& scratch);

} // namespace lsdem
