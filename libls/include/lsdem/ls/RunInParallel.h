/// @file RunInParallel.h
/// @brief Independent jobs run in parallel with the outcome of running them one by one: of
///        the jobs that throw, the first in index order is the one reported.
#pragma once

#include <tbb/parallel_for.h>

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
};

/// Calls @a job(k) for every k in [0, @a count), in parallel, and returns the first failure in
/// index order. Every job runs, also after one has failed (they are independent), and an
/// exception never escapes a worker thread.
template <typename Job>
FirstFailure runInParallel(size_t count, Job&& job)
{
    std::vector<std::exception_ptr> errors(count);
    tbb::parallel_for(size_t(0), count, [&](size_t k) {
        try {
            job(k);
        } catch (...) {
            errors[k] = std::current_exception();
        }
    });
    for (size_t k = 0; k < count; ++k)
        if (errors[k]) return {k, errors[k]};
    return {count, nullptr};
}

} // namespace lsdem
