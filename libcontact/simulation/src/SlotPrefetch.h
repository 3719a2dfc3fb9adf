// Fetching a contact slot's scattered state into the cache ahead of its turn.
//
// Why: a slot's shear histories live in the world's maps and its remembered candidate nodes
// in arrays of their own, each a separate allocation; where grains flow, contacts come and go
// and these end up scattered over the heap. A slot's work is too short to hide fetching them
// from memory when it needs them (a silo's discharge, one thread: 471 s before, 413 s after
// the backend asked for them ahead; docs/dynamics.md#speed). Asking only moves data into the
// cache: no result depends on it.
#pragma once

#include "lsdem/simulation/ContactList.h"

#include <algorithm>
#include <vector>

namespace lsdem {

/// The front of @a data, at most a few cache lines, asked for (@a kForWriting: to be written).
template <int kForWriting, typename T>
void prefetchFront(const std::vector<T>& data)
{
    constexpr size_t kLine = 64, kMostLines = 4;
    const char* front = reinterpret_cast<const char*>(data.data());
    const size_t lines = std::min(kMostLines, (data.size() * sizeof(T) + kLine - 1) / kLine);
    for (size_t l = 0; l < lines; ++l) __builtin_prefetch(front + l * kLine, kForWriting);
}

/// The first stage, two slots ahead: slot @a s's shear histories (the contact law rewrites
/// them).
inline void prefetchHistories(const ContactSlot& s)
{
    if (s.pairHistory) {
        const char* history = reinterpret_cast<const char*>(s.pairHistory);
        __builtin_prefetch(history, 1);
        __builtin_prefetch(history + sizeof(PairHistory) - 1, 1);
    }
    if (s.boundaryHistory) __builtin_prefetch(s.boundaryHistory, 1);
}

/// The second stage, one slot ahead (its histories are in the cache by then): the arrays
/// slot @a s's histories and remembered nodes point to.
inline void prefetchArrays(const ContactSlot& s)
{
    if (s.pairHistory) {
        prefetchFront<0>(s.pairHistory->shearOnFirstNodes.entries());
        prefetchFront<0>(s.pairHistory->shearOnSecondNodes.entries());
    }
    if (s.boundaryHistory) prefetchFront<0>(s.boundaryHistory->entries());
    for (const CandidateBlocks* c : {&s.candidates.ofFirst, &s.candidates.ofSecond}) {
        prefetchFront<0>(c->runs);
        prefetchFront<1>(c->cells);  // (their corner values are refreshed as nodes are sampled)
    }
}

} // namespace lsdem
