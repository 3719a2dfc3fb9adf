/// @file NumberText.h
/// @brief A number as the programs print it in messages: the stream's default (6 significant
///        digits), so a value reads the way the user typed it.
#pragma once

#include <sstream>
#include <string>

namespace lsdem::cli {

inline std::string numberText(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

} // namespace lsdem::cli
