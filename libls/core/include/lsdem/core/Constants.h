/// @file Constants.h
/// @brief Mathematical constants, spelled out once (C++17 has no std::numbers).
#pragma once

namespace lsdem {

inline constexpr double kPi = 3.14159265358979323846;

} // namespace lsdem
