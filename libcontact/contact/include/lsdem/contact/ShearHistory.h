/// @file ShearHistory.h
/// @brief The shear force each node of a contact carried out of the last step, kept as a flat
///        array sorted by node: the contact law walks it alongside the nodes now in contact
///        (which come in node order) and writes the next one into a buffer it swaps in, so a
///        step allocates nothing once the arrays have grown.
#pragma once

#include "lsdem/core/Vec3.h"

#include <initializer_list>
#include <vector>

namespace lsdem {

class ShearHistory
{
public:
    struct Entry
    {
        int node = 0;
        Vec3 force = Vec3::Zero();
        /// The spring's stiffness when the force was stored (0: not known, as in a checkpoint
        /// before version 10). A spring whose stiffness falls (a patch's area in contact
        /// shrinking) lets go of its force in proportion (springWithStiffness, ContactLaw.cpp).
        double stiffness = 0.0;
    };

    ShearHistory() = default;
    /// From entries in any order (sorted here); a node may appear once.
    ShearHistory(std::initializer_list<Entry> entries);

    bool empty() const { return mEntries.empty(); }
    size_t size() const { return mEntries.size(); }
    void clear() { mEntries.clear(); }
    const std::vector<Entry>& entries() const { return mEntries; }

    /// Whether @a node carries a shear force.
    bool contains(int node) const;
    /// The shear force of @a node (zero if it has none).
    Vec3 force(int node) const;

    /// Add @a node's force and its spring's stiffness; nodes must come in increasing order (as
    /// the contact law and a checkpoint give them). @throw std::invalid_argument otherwise.
    void append(int node, const Vec3& force, double stiffness = 0.0);

    /// Take @a next (whose entries must be sorted by node) as the history and hand the old
    /// buffer back in @a next, emptied, for reuse.
    void replaceWith(std::vector<Entry>& next);

private:
    std::vector<Entry> mEntries;  ///< sorted by node, each node once
};

/// Shear forces carried over between steps for each direction of testing of a grain pair.
struct PairHistory
{
    ShearHistory shearOnFirstNodes;   ///< nodes of the pair's first grain in the second
    ShearHistory shearOnSecondNodes;  ///< nodes of the second grain in the first

    bool empty() const { return shearOnFirstNodes.empty() && shearOnSecondNodes.empty(); }
};

} // namespace lsdem
