/// @file BatchBake.h
/// @brief Bake a folder of meshes (scans, generated grains) into assets and their catalogue:
///        one .vdb per file, in parallel over files, with voxel and node spacing optionally
///        relative to each grain's equivalent diameter; a bad file is reported and skipped; a
///        file whose bytes and options have not changed since the last run is not baked again.
#pragma once

#include "lsdem/ls/Bake.h"
#include "lsdem/ls/GrainCatalog.h"

#include <functional>
#include <string>
#include <vector>

namespace lsdem {

struct BatchBakeOptions
{
    /// Voxel size, node placement, areas, band and memory budget as for one file; voxelSize and
    /// nodeSpacing are replaced per grain when the per-size values below are set.
    BakeOptions bake;
    double voxelPerSize = 0.0;        ///< > 0: voxel = this × the grain's equivalent diameter
    double nodeSpacingPerSize = 0.0;  ///< > 0: node spacing = this × the equivalent diameter
    std::string outDir;               ///< assets NAME.vdb and catalog.csv go here
    int threads = 0;                  ///< files baked at once (and threads inside); 0: all cores
    bool rebake = false;              ///< bake every file, even if unchanged
};

/// The options as one canonical line ("voxel-per-size 0.03 nodes 600 areas mesh band 3"): the
/// catalogue keeps it, and a file is baked again when it changes.
std::string batchOptionsText(const BatchBakeOptions& options);

struct BatchFailure
{
    std::string source;   ///< the mesh file
    std::string message;  ///< why it was skipped
};

struct BatchBakeReport
{
    std::vector<CatalogEntry> entries;   ///< the whole catalogue as written, sorted by name
    std::vector<BatchFailure> failures;  ///< in input order
    std::vector<std::string> warnings;   ///< each naming its file
    int baked = 0, unchanged = 0;        ///< files baked now, files skipped as up to date
    std::string catalogPath;
};

/// Called after each file (from one thread at a time): files done so far, total, the file.
using BatchProgress = std::function<void(size_t done, size_t total, const std::string& file)>;

/// Bake @a meshPaths into options.outDir. Asset names are the files' stems (grain_0003.stl →
/// grain_0003.vdb); two inputs with one stem are refused before any work. The catalogue
/// (outDir/catalog.csv, written atomically at the end) holds a row per asset baked or found
/// unchanged, plus the rows of an earlier catalogue for other files, sorted by name; a failed
/// file keeps its earlier row if its earlier asset is still there, and has no row otherwise. Results do not depend on the thread count (except bake_seconds).
/// @throw Error for options that are wrong for every file (nothing is baked then).
BatchBakeReport bakeBatch(const std::vector<std::string>& meshPaths,
                          const BatchBakeOptions& options, const BatchProgress& progress = {});

} // namespace lsdem
