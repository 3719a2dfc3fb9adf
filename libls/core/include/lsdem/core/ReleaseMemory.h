/// @file ReleaseMemory.h
/// @brief Hand the pages that freed blocks leave wholly empty back to the system.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace lsdem {

/// malloc keeps what a stage frees in its heaps (one per thread that allocated), where only
/// that thread's next allocations can reuse it; handing the empty pages back lets the next
/// stage, on any thread, take them instead of growing the process. A no-op off glibc.
inline void releaseFreedMemory()
{
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

} // namespace lsdem
