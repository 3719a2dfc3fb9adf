/// @file ThreadPrivate.h
/// @brief A value one thread writes and no other touches (its scratch buffers), followed by
///        room enough that the next thread's copy never shares its neighbourhood.
///
/// Why: tbb::enumerable_thread_specific pads each thread's copy to 128 bytes and lays the
/// copies out one after another. With the two threads' contact scratch in adjacent 128-byte
/// blocks, the contact laws took about 20 % more time on 2 threads than on 1 on the 2-core
/// machine; with 256 bytes of room after each (copies 384 bytes apart), 1–5 % (bench_dynamics,
/// docs/dynamics.md#speed). Room, not alignment: TBB's allocator does not honour alignment
/// above 128 bytes.
#pragma once

#include <cstddef>

namespace lsdem {

/// Bytes kept free after a thread's private value.
inline constexpr size_t kThreadPrivateSpacing = 256;

template <typename T>
struct ThreadPrivate
{
    T value{};
    char spacing[kThreadPrivateSpacing] = {};  ///< never used: keeps the next copy away
};

} // namespace lsdem
