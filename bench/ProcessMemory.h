/// @file ProcessMemory.h
/// @brief This process's resident memory from /proc/self/status, for the benchmarks' memory
///        figures (they include what malloc keeps, not what it gave back).
#pragma once

#include <fstream>
#include <malloc.h>
#include <sstream>
#include <string>

namespace lsdem::bench {

constexpr double kMiB = 1024.0 * 1024.0;

/// A field of /proc/self/status in bytes (VmRSS: resident now, VmHWM: the high-water mark);
/// 0 if it cannot be read.
inline double statusBytes(const std::string& field)
{
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind(field + ":", 0) == 0) {
            std::istringstream in(line.substr(field.size() + 1));
            double kib = 0;
            in >> kib;
            return kib * 1024.0;
        }
    return 0.0;
}

/// Reset the high-water mark to the present resident size (Linux ≥ 4.0), so VmHWM afterwards
/// is the peak of what runs in between. Freed heap is handed back first, so memory reused
/// from earlier work counts too.
inline void resetPeakRss()
{
    malloc_trim(0);
    std::ofstream("/proc/self/clear_refs") << "5";
}

} // namespace lsdem::bench
