/// @file FuzzSupport.h
/// @brief What every fuzz target shares: the libFuzzer entry point, a private scratch file for
///        loaders that only take a path, and the check that a refusal is a clear lsdem::Error.
#pragma once

#include "lsdem/core/Error.h"

#include <cstddef>
#include <cstdint>
#include <string>

/// libFuzzer's entry point, defined once per target; the replay program calls it too.
/// Returns 0; anything that is not a clean result or a clear lsdem::Error escapes or aborts.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace lsdem::fuzz {

/// Write @a size bytes to a file named "input<extension>" in a folder private to this process
/// (in /dev/shm when there is one: thousands of rewrites a second stay off the disk), and return
/// its path. The folder is removed when the process exits normally.
std::string writeScratchFile(const std::uint8_t* data, std::size_t size,
                             const std::string& extension);

/// Abort (a finding) unless @a error says where and what: a refusal must be readable.
void requireClearError(const Error& error);

} // namespace lsdem::fuzz
