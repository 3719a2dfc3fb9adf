/// @file AtomicFile.h
/// @brief Write a result file so that readers see either the old file or the whole new one,
///        never a half-written one: write to a temporary beside it, then rename.
#pragma once

#include <functional>
#include <string>

namespace lsdem {

/// Call @a writeTo with a temporary path in the folder of @a path; if it returns normally,
/// rename the temporary to @a path. If it throws, the temporary is removed and the exception
/// passes on, so @a path is untouched.
/// @throw Error if the folder does not exist or is not writable.
void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tmpPath)>& writeTo);

/// Text version: writes @a contents.
void writeTextFileAtomically(const std::string& path, const std::string& contents);

} // namespace lsdem
