/// @file WorldFingerprint.h
/// @brief What a world was built from, reduced to numbers a checkpoint keeps: for each grain
///        one for itself (its name, material, motion and mass) and one for its asset (the
///        level set's bounds, mass properties and nodes), and for each boundary one for its
///        level set, if it has one. A restart rebuilds its world from the scene's files as
///        they are then; comparing the numbers tells whether those files still make the world
///        the run was checkpointed with. Assets no grain or boundary uses do not count (a
///        folder of assets may grow between a stop and its restart).
#pragma once

#include "lsdem/simulation/World.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lsdem {

struct WorldFingerprint
{
    std::vector<uint64_t> grains;          ///< per grain: name, material, motion, mass
    std::vector<uint64_t> grainAssets;     ///< per grain: its asset
    std::vector<uint64_t> boundaryAssets;  ///< per boundary: its level set's asset (0: none)
};

/// The fingerprint of @a world's assets and grains (not of their state, which a checkpoint
/// stores whole).
WorldFingerprint fingerprintOf(const World& world);

/// @throw Error at @a path (the checkpoint) naming the first grain or boundary of @a world
///        that differs from @a stored, and why that matters. Assets are compared only when
///        @a stored has their fingerprints (a checkpoint of an earlier format may not).
void checkSameInputs(const WorldFingerprint& stored, const World& world, const std::string& path);

} // namespace lsdem
