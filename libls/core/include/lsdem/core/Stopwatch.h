/// @file Stopwatch.h
/// @brief Wall-clock time of a piece of work, on the steady clock (never jumps with the date),
///        for the figures the programs and studies report.
#pragma once

#include <chrono>

namespace lsdem {

using SteadyClock = std::chrono::steady_clock;

/// Seconds from @a start until now.
inline double secondsSince(SteadyClock::time_point start)
{
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

/// Started when made; seconds() since then, restart() to begin again.
class Stopwatch
{
public:
    double seconds() const { return secondsSince(mStart); }
    void restart() { mStart = SteadyClock::now(); }

private:
    SteadyClock::time_point mStart = SteadyClock::now();
};

} // namespace lsdem
