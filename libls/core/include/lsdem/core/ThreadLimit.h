/// @file ThreadLimit.h
/// @brief The most worker threads any lsdem program or the Python module takes.
#pragma once

namespace lsdem {

/// More is a typo, and TBB would try to allocate for all of them (std::bad_alloc for
/// 99999999999).
constexpr int kMaxThreads = 1024;

} // namespace lsdem
