/// @file GrainsCsv.h
/// @brief Grains as a CSV table, one grain a row: for packings measured in a CT scan or made by
///        another code (or by lsdem-pack), read into a scene by [[grain_files]].
///
///        Columns, by name in the header row, in any order: `asset`, `x`, `y`, `z` (the
///        centroid), `qw`, `qx`, `qy`, `qz` (the unit quaternion asset → world) are required;
///        `name`, `material`, `vx`, `vy`, `vz`, `wx`, `wy`, `wz` are optional. Any other column
///        is refused (a misspelt one would be lost silently). Numbers must be finite; a
///        quaternion may be off unit length by up to 1e-4 (text written with 6 digits) and is
///        normalised.
#pragma once

#include "lsdem/scene/Scene.h"

#include <string>

namespace lsdem {

/// Read the grains of CSV @a text (from @a path, for messages) and append them to @a scene with
/// material @a material (unless the row names one). Assets and materials are looked up by name
/// in @a scene.
/// @throw Error naming "path:line" and the column for a missing column, an unknown asset or
///        material, a value that is not a finite number, a bad quaternion or a short row.
void readGrainsCsv(const std::string& text, const std::string& path, int material, Scene& scene);

/// The CSV text of scene.grains[first, first + count): name (if any grain has one), asset,
/// x, y, z, qw, qx, qy, qz, and vx, vy, vz / wx, wy, wz if any grain moves; numbers in their
/// shortest exact form, so the file reads back to the same grains.
std::string grainsCsvText(const Scene& scene, size_t first, size_t count);

/// Write grainsCsvText(@a scene, @a first, @a count) to @a path atomically.
void writeGrainsCsv(const Scene& scene, size_t first, size_t count, const std::string& path);

} // namespace lsdem
