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

/// The membrane's triangles binned in a uniform grid of cells, rebuilt as it moves, so a node
/// finds the triangles near it in its own cell: each triangle is binned in every cell its box,
/// grown by the reach, overlaps. The cells are as wide as the mean grown box, so a node's cell
/// holds a few dozen triangles, of which it tests those whose box holds it.
class MembraneTriangleGrid
{
public:
    /// Bin @a m's triangles now; a node is tested against the triangles within @a reach
    /// (> 0, length): a node that far outside the membrane has escaped and is not pushed back.
    void build(const Membrane& m, double reach);
    /// The triangles binned in the cell of @a x (none: empty): those whose grown box may hold
    /// it (holds() tells).
    const std::vector<int>& near(const Vec3& x) const { return inCell(cellOf(x)); }
    /// The same in two parts, so a run of nodes in one cell looks it up once: the key of the
    /// cell of @a x (-1 outside every grown box), and the triangles binned in cell @a key.
    std::int64_t cellOf(const Vec3& x) const;
    const std::vector<int>& inCell(std::int64_t key) const;
    /// Whether triangle @a t's grown box holds @a x.
    bool holds(int t, const Vec3& x) const
    {
        const auto& [low, high] = mBoxes[size_t(t)];
        return (x.array() >= low.array()).all() && (x.array() <= high.array()).all();
    }
    /// Whether a sphere (centre @a c, radius @a r) may hold a node near a triangle.
    bool mayTouch(const Vec3& c, double r) const;
    double reach() const { return mReach; }

private:
    std::int64_t keyOf(long long i, long long j, long long k) const;

    double mReach = 0.0, mCell = 0.0;
    Vec3 mLow = Vec3::Zero(), mHigh = Vec3::Zero();  ///< the grown boxes' union
    std::vector<std::int64_t> mKeys;                 ///< sorted cell keys ...
    std::vector<std::vector<int>> mTriangles;        ///< ... and their triangles
    std::vector<std::pair<Vec3, Vec3>> mBoxes;       ///< each triangle's grown box
    std::vector<int> mNone;
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
/// in @a grid, under @a model (μ ignored): the nodes outside it within the grid's reach, depth
/// their distance from the plane of the nearest triangle, normal that triangle's inward one.
/// The membrane moves under the grain at the mean velocity of the points its nodes met.
/// @param dt the step (for the dashpot's dissipation; no shear is carried)
void computeMembraneContact(const ContactGrain& grain, const Membrane& m,
                            const MembraneTriangleGrid& grid, const ContactModel& model,
                            double dt, MembraneGrainContact& out, ContactScratch& scratch);

} // namespace lsdem
