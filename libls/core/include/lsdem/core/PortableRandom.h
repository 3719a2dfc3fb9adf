/// @file PortableRandom.h
/// @brief Random numbers that are the same on every machine and standard library: a 64-bit
///        Mersenne twister (its raw output is fixed by the C++ standard) with our own uniform
///        and normal transforms (std::uniform_real_distribution and std::normal_distribution
///        are not specified bit for bit, so libstdc++ and libc++ draw different numbers), and
///        SplitMix64 to derive independent streams from (seed, index).
#pragma once

#include "lsdem/core/Constants.h"

#include <cmath>
#include <cstdint>
#include <random>

namespace lsdem {

/// One step of SplitMix64 (Steele, Lea, Flood 2014): a bijective mix of 64 bits.
inline uint64_t splitMix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

class PortableRandom
{
public:
    explicit PortableRandom(uint64_t seed) : mEngine(seed) {}

    /// The stream for item @a index of a run seeded with @a seed: item i draws the same numbers
    /// whatever the number of items or the order in which they are made.
    static PortableRandom stream(uint64_t seed, uint64_t index)
    {
        return PortableRandom(splitMix64(splitMix64(seed) ^ splitMix64(index + 1)));
    }

    /// Uniform in [0, 1): the top 53 bits of the next raw output.
    double uniform() { return static_cast<double>(mEngine() >> 11) * 0x1.0p-53; }

    /// Standard normal (Box–Muller, one value per call).
    double normal()
    {
        const double u1 = 1.0 - uniform();  // (0, 1]: the logarithm stays finite
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
    }

private:
    std::mt19937_64 mEngine;
};

} // namespace lsdem
