/// @file GrainCatalog.h
/// @brief The shape measures of a baked grain and the catalogue of a baked set (catalog.csv,
///        one row per asset), as lsdem-bake writes it and scenes read it ([asset_sets]).
#pragma once

#include "lsdem/ls/GrainAsset.h"

#include <string>
#include <vector>

namespace lsdem {

/// Size and shape of a baked grain, from its asset.
struct GrainMeasures
{
    double volume = 0.0;              ///< of the input polyhedron, length³
    double surfaceArea = 0.0;         ///< sum of the node areas (the node mesh's area), length²
    double equivalentDiameter = 0.0;  ///< of the sphere of equal volume, (6V/π)^(1/3)
    /// Extents of the surface nodes along the principal axes, sorted long ≥ intermediate ≥ short.
    double lengthLong = 0.0, lengthIntermediate = 0.0, lengthShort = 0.0;
    double elongation = 0.0;          ///< intermediate / long (Zingg)
    double flatness = 0.0;            ///< short / intermediate (Zingg)
    double sphericity = 0.0;          ///< Wadell's: area of the equal-volume sphere / area
};

GrainMeasures measureGrain(const GrainAsset& asset);

/// One row of catalog.csv.
struct CatalogEntry
{
    std::string name;          ///< the asset's name (its source file's stem)
    std::string asset;         ///< the .vdb file, relative to the catalogue's folder
    std::string source;        ///< the input mesh, as given to lsdem-bake
    std::string sourceSha256;  ///< of the input's bytes
    std::string bakeOptions;   ///< the batch's bake options (a change re-bakes the asset)
    GrainMeasures measures;
    long long nodes = 0;       ///< surface node count
    double vdp = 0.0;          ///< voxel size
    double sdp = 0.0;          ///< mean nearest-neighbour node spacing
    double bakeSeconds = 0.0;  ///< wall time of the bake (0 when not known)
};

/// The row for @a asset saved as @a assetFile (relative to the catalogue) under @a name.
CatalogEntry catalogEntry(const GrainAsset& asset, const std::string& name,
                          const std::string& assetFile, const std::string& bakeOptions,
                          double bakeSeconds);

/// The catalogue's columns, in the order written.
const std::vector<std::string>& catalogColumns();

/// Write @a entries to @a path as CSV (header + one row each), atomically; numbers in their
/// shortest form that reads back to the same double.
void writeCatalog(const std::string& path, const std::vector<CatalogEntry>& entries);

/// Read a catalogue. The columns `name` and `asset` are required, the others optional (0 or ""
/// when absent) and in any order; unknown columns are ignored. Every row must have as many
/// fields as the header, a non-empty unique name and asset, and finite numbers.
/// @throw Error naming the file, the line and the column.
std::vector<CatalogEntry> readCatalog(const std::string& path);

} // namespace lsdem
