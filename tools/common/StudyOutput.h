/// @file StudyOutput.h
/// @brief The output folder of a study driver: checked before any work starts, but created
///        (and cleared of the study's files from an earlier run) only when the first result is
///        written, so input refused along the way (found by a bake or a plan) leaves no empty
///        folder behind and the earlier results untouched.
#pragma once

#include <string>
#include <vector>

namespace lsdem::cli {

/// Check, before any work, that the output folder @a dir could be created and written: it, or
/// the nearest of its parents that exists, must be a writable folder. Creates nothing.
/// @throw Error naming @a dir otherwise (fix: choose another --out).
void checkOutputFolder(const std::string& dir);

/// The files a study writes into its output folder: names relative to it ("scene/grains.csv"),
/// in which '*' stands for any characters but '/' ("cube27_*_by_nodes.png").
using StudyFiles = std::vector<std::string>;

/// Remove @a file, written by an earlier run of the study. @throw Error naming it if it stays.
void removeEarlierRunFile(const std::string& file);

/// Create @a dir (and its parents), check that it is writable, and remove the files matching
/// @a ownFiles that an earlier run of the study left there, so the folder holds this run's
/// outputs only (no plot of a formulation not run this time, no scene not asked for). Call it
/// once every input is checked, just before the first file is written. Files matching no
/// pattern (the user's) and folders are kept; how many went is printed unless @a quiet.
/// @throw Error naming @a dir or a file.
void prepareOutputFolder(const std::string& dir, const StudyFiles& ownFiles, bool quiet);

} // namespace lsdem::cli
