/// @file StudyLimits.h
/// @brief What the studies refuse before they start, the same for all of them: a plan over
///        kMaxStudySteps time steps would run for years (absurd but finite options: a crawling
///        wall, a microscopic time step). (Threads: kMaxThreads, lsdem/core/ThreadLimit.h.)
#pragma once

namespace lsdem {

constexpr long long kMaxStudySteps = 1000000000LL;

} // namespace lsdem
