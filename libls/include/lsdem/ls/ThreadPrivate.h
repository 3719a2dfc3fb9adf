/// @file ThreadPrivate.h
/// @brief A value one thread writes and no other touches (its scratch buffers), followed by
///        room enough that the next thread's copy never shares its neighbourhood.
///
/// Why: tbb::enumerable_thread_specific pads each thread's copy to 128 bytes and lays the
/// copies out one after another. With the two threads' contact scratch in adjacent 128-byte
/// blocks, the contact laws took about 20 % more time on 2 threads than on 1 on the 2-core
/// machine; with 256 bytes of room after each, 1–5 % (2026-11-25). Measured again on
/// 2026-11-27 the loss was 12–15 % of the symmetric narrow phase, all of it in the contact
/// laws, and a page of room (copies never in one 4 KiB page) took it to 0–3 %
/// (docs/dynamics.md#speed). Likely cause: the processor's streaming prefetcher, which fetches
/// lines ahead anywhere within a page, kept pulling the other thread's scratch (whose vector
/// ends it writes at every point force). Room, not alignment: TBB's allocator does not honour
/// alignment above 128 bytes.
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
