/// @file SceneFile.h
/// @brief Read a scene from a commented TOML file (toml++). Every key is checked: unknown keys,
///        wrong types, missing or bad values, unknown names and inconsistent units are
///        lsdem::Error naming the file, the line and the key, with the fix.
#pragma once

#include "lsdem/scene/Scene.h"

#include <string>

namespace lsdem {

/// Read and check the scene file @a path. Relative paths inside it are resolved from its folder.
/// @throw Error (file:line: key: problem / fix) for anything wrong.
Scene readSceneFile(const std::string& path);

/// Parse scene @a text as if it were the file @a path (used on restart, where the text comes
/// from the checkpoint, and by tests).
Scene parseScene(const std::string& text, const std::string& path);

/// Resolve the servo walls' area_walls (BoundarySpec::areaWallNames) to the indices of the named
/// walls, once every boundary is in @a scene: done by the reader; a scene built by a program
/// calls it after adding such a wall.
/// @throw Error if a named wall is unknown, not a plane, not perpendicular to the servo wall,
///        or the four do not form two opposite, perpendicular pairs.
void resolveServoAreaWalls(Scene& scene);

} // namespace lsdem
