/// @file WorldFingerprint.h
/// @brief What a world was built from, reduced to numbers a checkpoint keeps: one per asset
///        (its level set's bounds, mass properties and nodes) and one per grain (its name,
///        asset, material, motion and mass). A restart rebuilds its world from the scene's
///        files as they are then; comparing the numbers tells whether those files still make
///        the world the run was checkpointed with.
#pragma once

#include "lsdem/simulation/World.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lsdem {

struct WorldFingerprint
{
    std::vector<uint64_t> assets;  ///< per World::assets entry
    std::vector<uint64_t> grains;  ///< per grain
};

/// The fingerprint of @a world's assets and grains (not of their state, which a checkpoint
/// stores whole).
WorldFingerprint fingerprintOf(const World& world);

/// @throw Error at @a path (the checkpoint) naming the first asset or grain of @a world that
///        differs from @a stored, and why that matters.
void checkSameInputs(const WorldFingerprint& stored, const World& world, const std::string& path);

} // namespace lsdem
