/// @file StudyLimits.h
/// @brief What the studies refuse before they start, the same for all of them: more than
///        kMaxStudyThreads threads only exhaust memory starting them (the Python module's
///        kMaxThreads).
#pragma once

namespace lsdem {

constexpr long long kMaxStudyThreads = 1024;

} // namespace lsdem
