/// @file OrderedCollect.h
/// @brief Items gathered in parallel over fixed chunks of an index range and joined in chunk
///        order: the result is the same on any thread count, without a sort or a lock.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lsdem {

/// Calls @a collect(begin, end, out) for each chunk [begin, end) of [0, @a count), @a chunk
/// indices long (the last may be shorter), in parallel; each call appends its items to its
/// own @a out (a std::vector<T>&). Returns every chunk's items, joined in chunk order.
template <typename T, typename Collect>
std::vector<T> collectInOrder(size_t count, size_t chunk, Collect&& collect)
{
    std::vector<std::vector<T>> found((count + chunk - 1) / chunk);
    tbb::parallel_for(size_t(0), found.size(), [&](size_t c) {
        collect(c * chunk, std::min(count, (c + 1) * chunk), found[c]);
    });
    size_t total = 0;
    for (const std::vector<T>& part : found) total += part.size();
    std::vector<T> all;
    all.reserve(total);
    for (const std::vector<T>& part : found) all.insert(all.end(), part.begin(), part.end());
    return all;
}

} // namespace lsdem
