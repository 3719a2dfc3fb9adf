// What one evaluated contact slot hands to the other ranks (private to the simulation
// library, for ContactDecomposition): its result, its node-check counts, its point forces when
// they are recorded, and the shear history it leaves behind (state every rank must keep
// identical). Numbers travel as their bytes, so the receiver's copy is bit for bit the
// sender's; counts travel as variable-length integers (most are small).
#pragma once

#include "lsdem/simulation/ContactList.h"

#include <vector>

namespace lsdem::slotresults {

/// Whether every number of @a r is +0 (bit for bit): the result of a slot without contact
/// (sent as one flag; adding it to a sum that starts at +0 changes nothing).
bool isEmpty(const PairForces& r);

/// Append slot @a s to @a out (its point forces only if @a withForces).
void pack(const ContactSlot& s, bool withForces, std::vector<char>& out);

/// Read one slot packed by pack() from [@a at, @a end) into @a s (its result, stats, point
/// forces if @a withForces, and the shear history its pointers lead to); @a at moves past it.
/// @a buffer is working memory for the histories. @throw std::runtime_error if the bytes end
/// early (a bug, not an input error).
void unpack(const char*& at, const char* end, bool withForces, ContactSlot& s,
            std::vector<ShearHistory::Entry>& buffer);

} // namespace lsdem::slotresults
