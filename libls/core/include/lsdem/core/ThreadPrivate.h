/// @file ThreadPrivate.h
/// @brief A value one thread writes and no other touches (its scratch buffers), followed by
///        room enough that the next thread's copy never shares its neighbourhood.
///
/// Why: tbb::enumerable_thread_specific pads each thread's copy to only 128 bytes and lays the
/// copies out one after another, and the contact laws write their scratch (vector ends) at
/// every point force. Two threads' copies within one 4 KiB page made the same contacts cost
/// 12–20 % more on 2 threads than on 1 on the 2-core machine; copies in different pages,
/// 0–3 % (the streaming prefetcher fetches ahead anywhere within a page, the likely link;
/// docs/dynamics.md#speed has the measurements). Room, not alignment: TBB's allocator does
/// not honour alignment above 128 bytes.
#pragma once

#include <cstddef>

namespace lsdem {

/// Bytes kept free after a thread's private value: a page, so that no two threads' values
/// share one (prefetchers stay within a page).
inline constexpr size_t kThreadPrivateSpacing = 4096;

template <typename T>
struct ThreadPrivate
{
    T value{};
    char spacing[kThreadPrivateSpacing] = {};  ///< never used: keeps the next copy away
};

} // namespace lsdem
