// runInParallel: the outcome of one by one, whatever order the jobs fail in on the threads.
#include "lsdem/ls/RunInParallel.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

using namespace lsdem;

// Job 1 fails first in time (job 0 waits for it), job 0 after: job 0's failure is the one
// reported, with its own exception type.
TEST(RunInParallel, TheFirstFailureInIndexOrderIsReported)
{
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    std::atomic<bool> jobOneFailed{false};
    bool sawJobOneFail = false;
    const FirstFailure f = runInParallel(2, [&](size_t k) {
        if (k == 1) {
            jobOneFailed = true;
            throw std::logic_error("job 1");
        }
        const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (!jobOneFailed && std::chrono::steady_clock::now() < giveUp)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        sawJobOneFail = jobOneFailed;
        throw std::runtime_error("job 0");
    });
    ASSERT_TRUE(sawJobOneFail) << "the two jobs did not run side by side";
    EXPECT_EQ(f.index, 0u);
    ASSERT_TRUE(f.error);
    try {
        std::rethrow_exception(f.error);
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "job 0");
    } catch (...) {
        ADD_FAILURE() << "not job 0's exception";
    }
}

// As one by one: after a failure no later job is started; every job runs when none fails.
TEST(RunInParallel, NoJobAfterAFailureStartsAndAllRunWithout)
{
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    std::atomic<int> ran{0};
    const FirstFailure failed = runInParallel(100, [&](size_t k) {
        ++ran;
        if (k == 3) throw std::runtime_error("job 3");
    });
    EXPECT_EQ(failed.index, 3u);
    EXPECT_EQ(ran.load(), 4);

    ran = 0;
    const FirstFailure none = runInParallel(100, [&](size_t) { ++ran; });
    EXPECT_EQ(none.index, 100u);
    EXPECT_FALSE(none.error);
    EXPECT_EQ(ran.load(), 100);
}
