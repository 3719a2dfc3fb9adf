// The rules a run keeps for its output folder: what counts as a run's output, never replacing
// a file lsdem did not write or one of the scene's inputs, an earlier run's outputs replaced
// only when asked (--overwrite), a restart's frames kept beside their series, and a folder
// another run holds left alone. Private to lsdem_run (SimulationRun.cpp).
#pragma once

#include "lsdem/scene/Scene.h"

#include <string>
#include <vector>

namespace lsdem {
struct Checkpoint;
}

namespace lsdem::runfolder {

/// The checkpoint's name in the output folder.
inline const std::string kCheckpointFileName = "checkpoint.lsdem";

/// What a run finds in its output folder under the names of a run's outputs (each sorted).
struct OutputFolderFiles
{
    /// An earlier run's outputs (lsdem wrote them): a run there would leave some and replace
    /// others, so the folder would look like one run but hold two.
    std::vector<std::string> earlierRun;
    /// Files with other contents that this run would replace: somebody else's.
    std::vector<std::string> notOurs;
};

/// The files in @a outDir under the names of a run's outputs (of @a scene), sorted.
OutputFolderFiles scanOutputFolder(const std::string& outDir, const Scene& scene);

/// Refuses a run that would replace a file lsdem did not write, and (without @a overwrite) a
/// run into a folder holding an earlier run's outputs.
void refuseEarlierRun(const std::string& outDir, const OutputFolderFiles& found, bool overwrite);

/// Removes @a names from @a outDir (an earlier run's outputs, under --overwrite).
void removeEarlierRun(const std::string& outDir, const std::vector<std::string>& names);

/// Refuses a run whose outputs in @a outDir would replace one of the files @a scene reads (the
/// scene file, grain files, assets, meshes, catalogues).
void refuseOutputsOverInputs(const Scene& scene, const std::string& outDir, bool overwrite);

/// Refuses a restart writing into @a outDir when its frames.pvd, which lists the frames
/// written before the checkpoint, would name files only the checkpoint's folder holds.
void refuseFramesAwayFromTheirSeries(const Scene& scene, const Checkpoint& checkpoint,
                                     const std::string& restartPath, const std::string& outDir);

/// Refuses to go on in @a dir, which another run holds (FolderLock.h).
[[noreturn]] void refuseBusyFolder(const std::string& dir);

} // namespace lsdem::runfolder
