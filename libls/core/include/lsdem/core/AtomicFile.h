/// @file AtomicFile.h
/// @brief Write a result file so that readers see either the old file or the whole new one,
///        never a half-written one: write to a temporary beside it, then rename. And make sure
///        an output folder can be written before the work that fills it.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace lsdem {

/// Check that @a path can be written: its folder exists, is a folder and is writable, and
/// @a path is not a folder. Programs call it before long work whose result goes to @a path.
/// @throw Error naming @a path otherwise.
void checkOutputFile(const std::string& path);

/// Call @a writeTo with a temporary path in the folder of @a path; if it returns normally,
/// rename the temporary to @a path. If it throws, the temporary is removed and the exception
/// passes on, so @a path is untouched.
/// @throw Error as checkOutputFile does.
void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tmpPath)>& writeTo);

/// Stream version: @a write writes to a binary stream on the temporary. A stream that cannot be
/// opened or fails while writing (a full disk) is an Error naming @a path.
void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream& out)>& write);

/// Text version: writes @a contents.
void writeTextFileAtomically(const std::string& path, const std::string& contents);

/// Create @a dir (and its parents) and check that it is writable, before any work starts.
/// @throw Error naming the folder, with @a fix (e.g. "choose another --out").
void prepareOutputFolder(const std::string& dir, const std::string& fix);

} // namespace lsdem
