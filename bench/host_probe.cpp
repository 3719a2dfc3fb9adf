// host_probe: how dear it is, right now, for two CPUs of this machine to share data.
//
// On a virtual machine the host may place the two vCPUs where a cache line written by one
// takes many times longer to reach the other (docs/dynamics.md, "why 2 threads sometimes buy
// nothing"). A threaded lsdem-run then loses its second thread's gain, while one-thread runs
// and programs that share nothing between threads keep their speed. This prints, for the
// first two CPUs the process may run on:
//   - the round trip of one cache line bounced between them (a store seen, answered, seen);
//   - for each of the two, the time of one dependent load over an 8 MB set that the other
//     wrote last (past L2, within the L3 of a cache-sharing pair of cores).
// Run it beside a run whose speed you doubt: `for i in $(seq 20); do build/bench/host_probe; done`.
#include <sched.h>
#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

bool pinTo(int cpu)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

/// Median round trip, in ns, of a counter handed back and forth between @a a and @a b.
double roundTripNs(int a, int b)
{
    constexpr int kTrips = 20000, kBatches = 11;
    alignas(64) std::atomic<long> ball{0};
    std::vector<double> batches;
    std::thread answerer([&] {
        pinTo(b);
        for (long i = 0; i < long(kTrips) * kBatches; ++i) {
            while (ball.load(std::memory_order_acquire) != 2 * i + 1) {}
            ball.store(2 * i + 2, std::memory_order_release);
        }
    });
    pinTo(a);
    long i = 0;
    for (int batch = 0; batch < kBatches; ++batch) {
        const auto start = Clock::now();
        for (int k = 0; k < kTrips; ++k, ++i) {
            ball.store(2 * i + 1, std::memory_order_release);
            while (ball.load(std::memory_order_acquire) != 2 * i + 2) {}
        }
        batches.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
                          kTrips);
    }
    answerer.join();
    std::sort(batches.begin(), batches.end());
    return batches[batches.size() / 2];
}

/// A random cycle through @a lines cache lines: entry 8·i holds the index of the next line's.
std::vector<size_t> randomCycle(size_t lines)
{
    std::vector<size_t> order(lines);
    std::iota(order.begin(), order.end(), size_t(0));
    unsigned long long x = 0x9E3779B97F4A7C15ull;  // xorshift: the same cycle every run
    for (size_t i = lines - 1; i > 0; --i) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        std::swap(order[i], order[x % (i + 1)]);
    }
    std::vector<size_t> next(lines * 8);
    for (size_t i = 0; i < lines; ++i) next[order[i] * 8] = order[(i + 1) % lines] * 8;
    return next;
}

/// ns per dependent load on CPU @a reader over @a next, just rewritten by CPU @a writer.
double loadNs(std::vector<size_t>& next, int writer, int reader)
{
    std::thread([&] {
        pinTo(writer);
        for (size_t i = 0; i < next.size(); i += 8) next[i + 1] = i;  // own every line
    }).join();
    double ns = 0.0;
    size_t end = 0;
    std::thread([&] {
        pinTo(reader);
        const size_t loads = next.size() / 8;  // once round the cycle: each line read once
        size_t p = 0;
        const auto start = Clock::now();
        for (size_t i = 0; i < loads; ++i) p = next[p];
        ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count() / double(loads);
        end = p;
    }).join();
    return end == size_t(-1) ? -ns : ns;  // (keeps the chase from being optimized away)
}

} // namespace

int main()
{
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    sched_getaffinity(0, sizeof allowed, &allowed);
    std::vector<int> cpus;
    for (int c = 0; c < CPU_SETSIZE && cpus.size() < 2; ++c)
        if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
    if (cpus.size() < 2) {
        std::fprintf(stderr, "host_probe: needs two CPUs to run on; this process may use %zu\n",
                     cpus.size());
        return 1;
    }
    const int a = cpus[0], b = cpus[1];
    std::vector<size_t> cycle = randomCycle((8u << 20) / 64);
    loadNs(cycle, a, b);  // a first pass to fault the pages in
    const double trip = roundTripNs(a, b);
    const double readOnB = loadNs(cycle, a, b), readOnA = loadNs(cycle, b, a);
    std::printf("cpus %d,%d: line round trip %.0f ns; load of the other's 8 MB: on %d %.0f ns, "
                "on %d %.0f ns\n",
                a, b, trip, b, readOnB, a, readOnA);
    return 0;
}
