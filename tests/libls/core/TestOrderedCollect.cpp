// Items gathered in parallel, in chunk order: the same sequence on any thread count, whether
// joined at once (collectInOrder, returned or into a vector) or consumed a few chunks at a
// time (consumeInOrder).

#include "lsdem/core/OrderedCollect.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <vector>

namespace {

/// Chunk [begin, end) yields, for each index i in it, i % 3 copies of i: chunks of unequal
/// sizes, some indices yielding nothing.
void copiesOf(size_t begin, size_t end, std::vector<size_t>& out)
{
    for (size_t i = begin; i < end; ++i)
        for (size_t k = 0; k < i % 3; ++k) out.push_back(i);
}

std::vector<size_t> expected(size_t count)
{
    std::vector<size_t> all;
    copiesOf(0, count, all);
    return all;
}

TEST(OrderedCollect, JoinsChunksInOrderOnAnyThreadCount)
{
    for (const int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        EXPECT_EQ(lsdem::collectInOrder<size_t>(1001, 17, copiesOf), expected(1001));
    }
}

TEST(OrderedCollect, CollectsIntoAVectorReplacingItsItemsInItsOwnStorage)
{
    // Collected again and again into one vector (as the interior fill's layers are): each
    // time the items are the new ones only, and storage large enough already is kept.
    std::vector<size_t> into(5, 99);
    into.reserve(2000);
    const size_t* storage = into.data();
    for (const size_t count : {size_t(1001), size_t(40), size_t(0), size_t(700)}) {
        lsdem::collectInOrder<size_t>(count, 17, copiesOf, into);
        EXPECT_EQ(into, expected(count)) << count;
        EXPECT_EQ(into.data(), storage) << count;
    }
}

TEST(OrderedCollect, ConsumesInChunkOrderAFewChunksAtATime)
{
    // 59 chunks of 17 (the last shorter), consumed 1, 4 or all at a time: the same sequence.
    for (const int threads : {1, 2})
        for (const size_t atATime : {size_t(1), size_t(4), size_t(100)}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      size_t(threads));
            std::vector<size_t> consumed;
            lsdem::consumeInOrder<size_t>(1001, 17, atATime, copiesOf,
                                          [&](size_t item) { consumed.push_back(item); });
            EXPECT_EQ(consumed, expected(1001)) << threads << " threads, " << atATime;
        }
    std::vector<size_t> none;
    lsdem::consumeInOrder<size_t>(0, 17, 4, copiesOf, [&](size_t item) { none.push_back(item); });
    EXPECT_TRUE(none.empty());
}

} // namespace
