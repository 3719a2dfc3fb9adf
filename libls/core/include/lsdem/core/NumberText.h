/// @file NumberText.h
/// @brief A number as lsdem prints it: numberText, the shortest text that reads back to the
///        same double ("0.05", "5e-05", "1200"), for text files and values a user must be able
///        to type back; roundedText, a few significant digits, for messages and progress.
///        (std::to_string's six fixed decimals would print a voxel of 1e-07 m as "0.000000".)
#pragma once

#include <charconv>
#include <cstdio>
#include <string>

namespace lsdem {

inline std::string numberText(double v)
{
    char buffer[32];  // the longest double, "-2.2250738585072014e-308", has 24 characters
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

/// @a v to @a digits significant digits (printf's %g: 6 by default, as a stream prints it).
inline std::string roundedText(double v, int digits = 6)
{
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    return buffer;
}

} // namespace lsdem
