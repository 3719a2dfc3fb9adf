/// @file SceneChecks.h
/// @brief The checks across the sections of a scene (private to lsdem_scene): run by the file
///        reader on what it read, and by buildWorld on any scene, so a scene built in code
///        (Python, the studies) is held to the same rules as one read from a file.
#pragma once

#include "lsdem/scene/Scene.h"

namespace lsdem::scenefile {

/// Every pair of materials that can meet has one [[contacts]] entry.
void checkContactPairs(const Scene& scene);
/// Grains and boundaries have distinct names.
void checkUniqueNames(const Scene& scene);

} // namespace lsdem::scenefile
