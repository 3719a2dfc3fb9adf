/// @file GrainKeys.h
/// @brief The schema of a grain's keys (docs/scenes.md, [[grains]] and the grain keys of
///        [[lattices]]), written once for every front end: the scene reader gathers what an
///        entry gives, Python's add_grain what its arguments give, validateScene what a Scene
///        built in code holds (grainKeysOf), and all three ask applyGrainKeys, which names the
///        key at fault in the same words. The scene writer writes grainKeysOf.
#pragma once

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/Scene.h"

#include <optional>
#include <string>

namespace lsdem {

/// What a grain's entry gives, key by key, before any rule is applied (a key not given:
/// std::nullopt). The asset and material come as indices: each front end looks their names up.
struct GrainKeys
{
    std::string name;  ///< "" for the default name (grain<index>)
    int asset = -1, material = -1;
    std::optional<Vec3> position;     ///< required
    std::optional<Quat> orientation;  ///< asset frame to world; identity if not given
    std::optional<std::string> motion;  ///< "free" (the default), "fixed" or "prescribed"
    std::optional<Vec3> velocity, angularVelocity;
    std::optional<double> mass;  ///< >= 0; 0 (the default): density × the asset's volume
};

/// The first rule @a keys break: a position, finite vectors, a unit orientation, a known
/// motion, no velocity for a fixed grain, a mass >= 0. If none, @a out is the grain (its
/// `where` kept) and nothing is returned; otherwise @a out is left as it was.
std::optional<KeyProblem> applyGrainKeys(const GrainKeys& keys, GrainSpec& out);

/// The keys that give @a g: its asset, material, position and orientation, and the others where
/// they differ from their defaults. What the scene writer writes, and what validateScene checks.
GrainKeys grainKeysOf(const GrainSpec& g);

} // namespace lsdem
