/// @file StudyOutput.h
/// @brief The output folder of a study driver: checked before any work starts, but created
///        only when the first result is written, so input refused along the way (found by a
///        bake or a plan) leaves no empty folder behind.
#pragma once

#include <string>

namespace lsdem::cli {

/// Check, before any work, that the output folder @a dir could be created and written: it, or
/// the nearest of its parents that exists, must be a writable folder. Creates nothing.
/// @throw Error naming @a dir otherwise (fix: choose another --out).
void checkOutputFolder(const std::string& dir);

/// Create @a dir (and its parents) and check that it is writable: just before a study writes
/// its first file. @throw Error naming @a dir otherwise.
void prepareOutputFolder(const std::string& dir);

} // namespace lsdem::cli
