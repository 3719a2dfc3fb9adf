/// @file MembraneKeys.h
/// @brief The rules of a scene's [[membranes]] entry (Scene.h, MembraneSpec) and the world's
///        membrane made from it. The file reader, validateScene and Python ask the same rules,
///        so each refuses a value in the same words.
#pragma once

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/Membrane.h"

#include <optional>
#include <vector>

namespace lsdem {

/// The first rule @a m breaks on its own (its numbers; not its names, resolved elsewhere).
std::optional<KeyProblem> membraneProblem(const MembraneSpec& m);

/// The membrane @a m describes: its tube made and stretched round, its material, pressure and
/// drag set, and each of its rims held by the nearest of its @a m.hold boundaries of
/// @a boundaries (planes: the distance from the rim's centroid to the plane).
/// @throw Error (at @a m.where) if a holding boundary is not a plane or holds no rim.
Membrane makeMembrane(const MembraneSpec& m, const std::vector<BoundarySpec>& boundaries);

} // namespace lsdem
