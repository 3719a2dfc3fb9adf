/// @file SceneWriter.h
/// @brief Write a scene as a TOML file that readSceneFile reads back to the same scene: every
///        grain, boundary, contact law and setting, numbers in their shortest exact decimal
///        form, strings and names escaped. The counterpart of SceneFile.h, for programs that
///        build scenes (the studies, scripts) and hand them to lsdem-run. Grains read from a
///        CSV file ([[grain_files]]) are written as a reference to that file, which is kept.
#pragma once

#include "lsdem/scene/Scene.h"

#include <string>

namespace lsdem {

/// The TOML text of @a scene. Paths of asset and mesh files below @a sceneDirectory are written
/// relative to it (as the reader resolves them), others absolute. @a header, if not empty, is
/// written first as comment lines (a '#' is put before each line).
/// @throw Error if an asset is held only in memory (AssetSpec::loaded without a file: save it
///        first) or a number is not finite.
std::string sceneToToml(const Scene& scene, const std::string& sceneDirectory,
                        const std::string& header = "");

/// Write sceneToToml(@a scene, the folder of @a path, @a header) to @a path atomically.
void writeSceneFile(const Scene& scene, const std::string& path, const std::string& header = "");

} // namespace lsdem
