/// @file CatalogMixture.h
/// @brief A packing mixture of every asset of a catalogue (lsdem-bake --out-dir writes
///        DIR/catalog.csv), named as a scene's [asset_sets.SET] with that catalogue names them
///        ("SET/NAME"), so a packing made from it reads back into such a scene.
#pragma once

#include "lsdem/scene/Packing.h"

#include <string>
#include <vector>

namespace lsdem {

/// Load every asset of the catalogue @a catalog (its `asset` column is relative to the
/// catalogue's folder), in row order, each with fraction 1 and the name "@a setName/NAME".
/// @throw Error naming the catalogue (and its line) for a missing or empty catalogue, a bad
///        row, an asset file that does not exist or does not load, or a set name that is empty
///        or holds '/'.
std::vector<PackingComponent> catalogMixture(const std::string& catalog,
                                             const std::string& setName);

/// The asset files that the catalogue @a catalog lists, found as catalogMixture finds them,
/// whether they exist or not; none if @a catalog is not a file (catalogMixture says so).
/// @throw Error naming the catalogue and its line for a bad row.
std::vector<std::string> catalogAssetFiles(const std::string& catalog);

} // namespace lsdem
