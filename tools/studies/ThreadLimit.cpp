#include "studies/ThreadLimit.h"

#include "studies/RunDistributor.h"

#include <tbb/global_control.h>

namespace lsdem {

struct ThreadLimit::Control
{
    explicit Control(long long threads)
        : control(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads))
    {
    }
    tbb::global_control control;
};

ThreadLimit::ThreadLimit(long long requested, const RunDistributor& ranks)
    : mThreads(requested > 0 ? requested : ranks.threadsPerRank())
{
    if (mThreads > 0) mControl = std::make_unique<Control>(mThreads);
}

ThreadLimit::~ThreadLimit() = default;

std::string describeRanks(const RunDistributor& ranks, const ThreadLimit& threads)
{
    const long long t = threads.threads();
    return "spread over " + std::to_string(ranks.ranks()) + " ranks x " +
           (t > 0 ? std::to_string(t) + (t == 1 ? " thread" : " threads") : "all cores");
}

} // namespace lsdem
