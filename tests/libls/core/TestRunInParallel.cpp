// runInParallel: the outcome of one by one, whatever order the jobs fail in on the threads.
#include "lsdem/core/RunInParallel.h"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

using namespace lsdem;

// Job 1 fails first in time (job 0 waits for it), job 0 after: job 0's failure is the one
// reported, with its own exception type.
TEST(RunInParallel, TheFirstFailureInIndexOrderIsReported)
{
    tbb::task_arena twoThreads(2);  // a worker's place kept, whatever other tests left running
    std::atomic<bool> jobOneFailed{false};
    bool sawJobOneFail = false;
    FirstFailure f;
    twoThreads.execute([&] {
        f = runInParallel(2, [&](size_t k) {
            if (k == 1) {
                jobOneFailed = true;
                throw std::logic_error("job 1");
            }
            const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
            while (!jobOneFailed && std::chrono::steady_clock::now() < giveUp)
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            sawJobOneFail = jobOneFailed;
            throw std::runtime_error("job 0");
        });
    });
    if (!sawJobOneFail)  // a process allowed one CPU has no worker thread to run job 1
        GTEST_SKIP() << "the two jobs did not run side by side (one CPU?)";
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

// On one thread, as one by one: after a failure no later job is started; every job runs when
// none fails.
TEST(RunInParallel, NoJobAfterAFailureStartsAndAllRunWithout)
{
    tbb::task_arena oneThread(1);  // this thread alone: the jobs run in index order
    std::atomic<int> ran{0};
    FirstFailure failed;
    oneThread.execute([&] {
        failed = runInParallel(100, [&](size_t k) {
            ++ran;
            if (k == 3) throw std::runtime_error("job 3");
        });
    });
    EXPECT_EQ(failed.index, 3u);
    EXPECT_EQ(ran.load(), 4);

    ran = 0;
    FirstFailure none;
    oneThread.execute([&] { none = runInParallel(100, [&](size_t) { ++ran; }); });
    EXPECT_EQ(none.index, 100u);
    EXPECT_FALSE(none.error);
    EXPECT_EQ(ran.load(), 100);
}
