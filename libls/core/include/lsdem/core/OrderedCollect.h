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
/// own @a out (a std::vector<T>&). Puts every chunk's items, joined in chunk order, into
/// @a all (its items replaced, its storage kept: a loop that collects again and again reuses
/// one block instead of leaving a freed one behind each time, which smaller blocks allocated
/// meanwhile would split).
template <typename T, typename Collect>
void collectInOrder(size_t count, size_t chunk, Collect&& collect, std::vector<T>& all)
{
    std::vector<std::vector<T>> found((count + chunk - 1) / chunk);
    tbb::parallel_for(size_t(0), found.size(), [&](size_t c) {
        collect(c * chunk, std::min(count, (c + 1) * chunk), found[c]);
    });
    size_t total = 0;
    for (const std::vector<T>& part : found) total += part.size();
    all.clear();
    all.reserve(total);
    for (const std::vector<T>& part : found) all.insert(all.end(), part.begin(), part.end());
}

/// The same, returned.
template <typename T, typename Collect>
std::vector<T> collectInOrder(size_t count, size_t chunk, Collect&& collect)
{
    std::vector<T> all;
    collectInOrder(count, chunk, collect, all);
    return all;
}

/// The same items, handed to @a consume(item) on the calling thread in chunk order, gathered
/// @a chunksAtATime chunks at a time (those in parallel): no more than their items are held at
/// once.
template <typename T, typename Collect, typename Consume>
void consumeInOrder(size_t count, size_t chunk, size_t chunksAtATime, Collect&& collect,
                    Consume&& consume)
{
    const size_t chunks = (count + chunk - 1) / chunk;
    std::vector<std::vector<T>> found(std::min(chunks, std::max<size_t>(chunksAtATime, 1)));
    for (size_t first = 0; first < chunks; first += found.size()) {
        const size_t last = std::min(chunks, first + found.size());
        tbb::parallel_for(first, last, [&](size_t c) {
            std::vector<T>& out = found[c - first];
            out.clear();
            collect(c * chunk, std::min(count, (c + 1) * chunk), out);
        });
        for (size_t c = first; c < last; ++c)
            for (const T& item : found[c - first]) consume(item);
    }
}

} // namespace lsdem
