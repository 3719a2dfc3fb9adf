/// @file Checkpoint.h
/// @brief Save and restore everything a run needs to continue bit-identically: the scene's
///        text, the step, every grain's state and last force, the boundaries, the shear
///        history of every contact, the energy bookkeeping and the run's output state.
///        Binary (doubles stored exactly), versioned, written atomically.
#pragma once

#include "lsdem/run/RunRecord.h"
#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

struct Checkpoint
{
    std::string scenePath;  ///< the scene file the run started from (relative paths in it
                            ///< are resolved from its folder)
    std::string sceneText;
    double timeStep = 0.0;
    RunRecord record;
    /// When the run ends. A run may be given an end other than its scene text's (lsdem-run
    /// --end-time, Python's scene.end_time after loading); a restart continues to this one.
    /// None: the scene text's (checkpoints before version 4).
    std::optional<EndCondition> end;
    /// The whole file, as readCheckpoint read it (empty in a checkpoint to be saved). The
    /// world's state is restored from these bytes, not from a second reading of the file: a
    /// run still writing the folder may replace the file meanwhile, and the history rows above
    /// must come from the same checkpoint as the state that continues them.
    std::string fileBytes;
};

/// Write @a world and @a checkpoint to @a path atomically.
void saveCheckpoint(const std::string& path, const World& world, const Checkpoint& checkpoint);

/// Whether the file at @a path begins as a checkpoint does (whole or not).
bool isCheckpointFile(const std::string& path);

/// Read the checkpoint at @a path, once: its header (scene, time step, run record) and, in
/// fileBytes, the whole file for restoreWorldState.
/// @throw Error naming the file if it is missing, truncated or not an lsdem checkpoint.
Checkpoint readCheckpoint(const std::string& path);

/// As readCheckpoint, from the file's @a bytes read elsewhere (split over ranks, rank 0 reads
/// the file and the others get its bytes); @a path names the file in errors.
Checkpoint parseCheckpoint(std::string bytes, const std::string& path);

/// Give @a scene (read from @a checkpoint's text) the end the run had, if the checkpoint kept
/// one. @throw Error naming @a path if that end names a boundary the scene lacks (damaged).
void applyCheckpointEnd(const Checkpoint& checkpoint, Scene& scene, const std::string& path);

/// Overwrite the dynamic state of @a world (built from the checkpoint's scene) with the state
/// stored in @a checkpoint (read by readCheckpoint or parseCheckpoint from @a path, which
/// errors name). On an Error @a world is left as it was.
/// @throw Error if the file does not match the world (grain or boundary counts differ).
void restoreWorldState(const Checkpoint& checkpoint, const std::string& path, World& world);

/// The same, reading the file at @a path (once).
void restoreWorldState(const std::string& path, World& world);

} // namespace lsdem
