/// @file NumberText.h
/// @brief A number as lsdem prints it in messages and text files: the shortest text that reads
///        back to the same double ("0.05", "5e-05", "1200"). std::to_string's six fixed decimals
///        would print a voxel of 1e-07 m as "0.000000".
#pragma once

#include <charconv>
#include <string>

namespace lsdem {

inline std::string numberText(double v)
{
    char buffer[32];  // the longest double, "-2.2250738585072014e-308", has 24 characters
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

} // namespace lsdem
