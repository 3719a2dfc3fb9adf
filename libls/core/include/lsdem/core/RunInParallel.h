/// @file RunInParallel.h
/// @brief Independent jobs run in parallel with the outcome of running them one by one: of
///        the jobs that throw, the first in index order is the one reported.
#pragma once

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cstddef>
#include <exception>
#include <vector>

namespace lsdem {

/// The first job, in index order, that threw: its index and exception (none: @a error is null
/// and @a index the job count).
struct FirstFailure
{
    size_t index = 0;
    std::exception_ptr error;

    /// Throw the failure's exception, if there was one.
    void rethrowIfAny() const
    {
        if (error) std::rethrow_exception(error);
    }
};

/// Calls @a job(k) for k in [0, @a count) in parallel, one job per task, and returns the first
/// failure in index order. As one by one would, once a failure is recorded no job after it
/// starts (those already running finish); every job before it runs, so the first failure is
/// exact. Each job runs isolated: a thread waiting inside one (its own parallel loops) takes
/// no other job, so no more jobs are alive at once than there are threads (a job may be a
/// bake of a large mesh).
template <typename Job>
FirstFailure runInParallel(size_t count, Job&& job)
{
    std::vector<std::exception_ptr> errors(count);
    std::atomic<size_t> firstFailed{count};
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, 1),
        [&](const tbb::blocked_range<size_t>& range) {
            for (size_t k = range.begin(); k != range.end(); ++k) {
                if (k > firstFailed.load()) return;
                try {
                    tbb::this_task_arena::isolate([&] { job(k); });
                } catch (...) {
                    errors[k] = std::current_exception();
                    size_t seen = firstFailed.load();
                    while (k < seen && !firstFailed.compare_exchange_weak(seen, k)) {
                    }
                }
            }
        },
        tbb::simple_partitioner());
    for (size_t k = 0; k < count; ++k)
        if (errors[k]) return {k, errors[k]};
    return {count, nullptr};
}

} // namespace lsdem
