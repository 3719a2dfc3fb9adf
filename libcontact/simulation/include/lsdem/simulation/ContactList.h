/// @file ContactList.h
/// @brief The contacts a simulation evaluates each step: grain pairs and grain–boundary pairs
///        within reach, kept over many steps with a skin (a Verlet list). The list is rebuilt
///        only when some grain or boundary has moved more than half the skin since the last
///        build; until then every pair whose bounding spheres can overlap is already on it, so
///        the forces are exactly those of a list rebuilt every step (pairs further apart get
///        no contact nodes and add nothing). It also knows, for each grain, its slots in list
///        order, so forces can be summed per grain in parallel and in a fixed order.
#pragma once

#include "lsdem/contact/CandidateBlocks.h"
#include "lsdem/contact/ContactLaw.h"
#include "lsdem/simulation/World.h"

#include <utility>
#include <vector>

namespace lsdem {

/// One contact to evaluate: a grain pair (boundary < 0) or a grain and a boundary, with its
/// shear history (in the world's maps, which do not move it while the list stands) and the
/// result of its last evaluation.
struct ContactSlot
{
    int first = 0, second = -1, boundary = -1;
    /// In a periodic cell, the periods (−1, 0 or 1 per axis) by which the pair touches across
    /// its faces: first touches second's image at second + periods ∘ the cell's size.
    Vec3 periods = Vec3::Zero();
    PairHistory* pairHistory = nullptr;
    ShearHistory* boundaryHistory = nullptr;
    PairForces result;
    NodeCheckStats stats;
    std::vector<PointForce> forces;  ///< point forces, when they are recorded
    PairCandidates candidates;  ///< nodes near the other grain or level-set obstacle, kept over steps
};

/// A grain's part in a slot: which slot, and whether the grain is its first body.
struct GrainSlotRef
{
    int slot = 0;
    bool first = true;
};

class ContactList
{
public:
    /// @param skinFraction the skin as a fraction of the median grain bounding radius
    explicit ContactList(double skinFraction = 0.25) : mSkinFraction(skinFraction) {}
    /// A copy (of a Simulation, say) starts unbuilt: the slots point into the shear
    /// histories of the world they were built for, not into the copy's.
    ContactList(const ContactList& other)
        : mSkinFraction(other.mSkinFraction), mFixedSkin(other.mFixedSkin), mOwned(other.mOwned)
    {
    }
    ContactList& operator=(const ContactList& other)
    {
        *this = ContactList(other);
        return *this;
    }
    /// The skin the list would choose for @a world (a fraction of its median bounding radius).
    double skinFor(const World& world) const;
    /// Use @a skin whatever the world holds: a rank holding part of the grains
    /// (GhostDecomposition.h) uses the whole simulation's, so its list is the one-process
    /// list's part.
    void fixSkin(double skin) { mFixedSkin = skin; }
    /// Keep only the pairs with a grain marked in @a owned (by grain index; null: every pair),
    /// and boundary contacts of marked grains: the contacts a rank owning those grains
    /// evaluates. @a owned must outlive the list or be replaced before the next rebuild.
    void restrictTo(const std::vector<char>* owned) { mOwned = owned; }
    /// Whether update() would rebuild: never built, marked stale, grains added or removed, or
    /// a grain or boundary moved more than half the skin since the build.
    bool needsRebuild(const World& world) const;
    ContactList(ContactList&&) = default;
    ContactList& operator=(ContactList&&) = default;

    /// Rebuild if the list is stale (never built, marked stale, or a grain or boundary moved
    /// more than half the skin since the build). Histories of pairs that left the list are
    /// dropped (they are empty: such pairs had no contact nodes); new pairs start empty.
    /// @return whether it was rebuilt
    bool update(World& world);
    /// Force a rebuild at the next update (the world was changed from outside).
    void markStale() { mBuilt = false; }
    /// The world's grains were renumbered (a rank's grains after a migration): grain i is now
    /// @a newIndex[i] (-1: gone), in the same order. Rebuild at the next update, the pairs
    /// still on the list keeping their node blocks (CandidateBlocks.h).
    void renumber(const std::vector<int>& newIndex);

    std::vector<ContactSlot>& slots() { return mSlots; }
    const std::vector<ContactSlot>& slots() const { return mSlots; }
    size_t pairSlotCount() const { return mPairSlots; }
    /// Grain @a g's slots in list order: [grainSlotsBegin(g), grainSlotsBegin(g + 1)).
    const GrainSlotRef* grainSlotsBegin(size_t g) const
    {
        return mGrainSlots.data() + mGrainSlotStart[g];
    }
    long long rebuilds() const { return mRebuilds; }
    double skin() const { return mSkin; }

private:
    /// @param keepPairKnowledge whether pairs still on the list keep their candidate node
    ///        blocks (only when the world's grains and assets are those of the last build)
    void rebuild(World& world, bool keepPairKnowledge);

    double mSkinFraction;
    double mFixedSkin = -1.0;  ///< >= 0: fixSkin's
    const std::vector<char>* mOwned = nullptr;
    double mSkin = 0.0;
    bool mBuilt = false;
    bool mRenumbered = false;  ///< the next rebuild keeps the pairs' knowledge anyway
    long long mRebuilds = 0;
    std::vector<Vec3> mGrainPositionsAtBuild, mBoundaryDisplacementsAtBuild;
    std::vector<ContactSlot> mSlots;  ///< grain pairs (sorted), then grain–boundary (sorted)
    size_t mPairSlots = 0;
    std::vector<size_t> mGrainSlotStart;     ///< per grain, into mGrainSlots (n + 1 entries)
    std::vector<GrainSlotRef> mGrainSlots;
};

} // namespace lsdem
