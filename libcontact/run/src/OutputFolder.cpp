// The output folder's rules for a run (OutputFolder.h).
#include "OutputFolder.h"

#include "FrameWriter.h"
#include "RunPlan.h"

#include "lsdem/core/Error.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/RunOutputs.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace lsdem::runfolder {

namespace fs = std::filesystem;
using namespace runplan;

namespace {

bool endsWith(const std::string& s, const std::string& end)
{
    return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

/// Whether any run writes a file called @a name into its output folder (whatever its scene).
bool isRunOutputName(const std::string& name)
{
    if (name == kEnergyFileName || name == kGrainsFileName || name == kCheckpointFileName ||
        name == kMicromechanicsFileName || name == kCellFileName ||
        name == kFramesBaseName + ".pvd" || isBoundaryHistoryFileName(name) ||
        isMembraneHistoryFileName(name))
        return true;
    // The frames and, split over ranks, their pieces: frames_grains_3.vtu, ..._3.pvtu, ..._3_1.vtu
    return name.rfind(kFramesBaseName + "_", 0) == 0 &&
           (endsWith(name, ".vtu") || endsWith(name, ".pvtu"));
}

/// Whether a run of @a scene may write a file called @a name into its output folder: its own
/// boundaries' and membranes' histories, its cell's if it has one, and every other output name
/// (frames counted whatever vtk_period).
bool runWrites(const Scene& scene, const std::string& name)
{
    if (name == kCellFileName) return scene.periodicCell.maxCoeff() > 0.0;
    if (isBoundaryHistoryFileName(name)) {
        for (const BoundarySpec& b : scene.boundaries)
            if (name == boundaryHistoryFileName(b.name)) return true;
        return false;
    }
    if (isMembraneHistoryFileName(name)) {
        for (const MembraneSpec& m : scene.membranes)
            if (name == membraneHistoryFileName(m.name)) return true;
        return false;
    }
    return isRunOutputName(name);
}

/// Whether the file at @a path begins as a VTK XML file does (frames.pvd and the frames).
bool isVtkFile(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string start(512, '\0');
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<size_t>(in.gcount()));
    return start.find("<VTKFile") != std::string::npos;
}

/// Whether the file at @a path, named as a run's output @a name, holds what lsdem writes there.
bool holdsRunOutput(const fs::path& path, const std::string& name)
{
    if (name == kCheckpointFileName) return isCheckpointFile(path.string());
    if (endsWith(name, ".csv")) return isRunTextOutput(path.string());
    return isVtkFile(path);
}

} // namespace

OutputFolderFiles scanOutputFolder(const std::string& outDir, const Scene& scene)
{
    OutputFolderFiles found;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(outDir, ec)) {
        const std::string name = entry.path().filename().string();
        if (!isRunOutputName(name) || entry.is_directory(ec)) continue;
        if (holdsRunOutput(entry.path(), name)) found.earlierRun.push_back(name);
        else if (runWrites(scene, name)) found.notOurs.push_back(name);
    }
    std::sort(found.earlierRun.begin(), found.earlierRun.end());
    std::sort(found.notOurs.begin(), found.notOurs.end());
    return found;
}

/// Refuses a run that would replace a file lsdem did not write, and (without @a overwrite) a
/// run into a folder holding an earlier run's outputs.
void refuseEarlierRun(const std::string& outDir, const OutputFolderFiles& found, bool overwrite)
{
    if (!found.notOurs.empty())
        throw Error((fs::path(outDir) / found.notOurs.front()).string(),
                    "this file is not an output of lsdem, and the run would replace it with "
                    "its own",
                    "move it away, or choose another --out");
    const std::vector<std::string>& earlier = found.earlierRun;
    if (earlier.empty() || overwrite) return;
    const size_t shown = std::min<size_t>(earlier.size(), 5);
    std::string names;
    for (size_t i = 0; i < shown; ++i) names += (i ? ", " : "") + earlier[i];
    if (earlier.size() > shown) names += " and " + std::to_string(earlier.size() - shown) + " more";
    throw Error(outDir,
                "the output folder holds the outputs of an earlier run (" + names +
                    "), which this run would mix with its own",
                "choose another --out, or pass --overwrite to replace them (run_scene: "
                "overwrite=True)");
}

/// Removes @a names from @a outDir (an earlier run's outputs, under --overwrite).
void removeEarlierRun(const std::string& outDir, const std::vector<std::string>& names)
{
    for (const std::string& name : names) {
        const fs::path path = fs::path(outDir) / name;
        std::error_code ec;
        fs::remove(path, ec);
        if (ec)
            throw Error(path.string(), "cannot remove this earlier output (" + ec.message() + ")",
                        "remove it yourself, or choose another --out");
    }
}

/// Refuses a run whose outputs in @a outDir would replace one of the files @a scene reads (the
/// scene file, grain files, assets, meshes, catalogues): e.g. a scene reading grains.csv from
/// its own folder, run with --out that folder. An input is replaced if it is listed in
/// @a outDir under an output's name (with @a overwrite: under any run's output name, as the
/// earlier run's outputs are removed), or is a link to such a file.
void refuseOutputsOverInputs(const Scene& scene, const std::string& outDir, bool overwrite)
{
    auto check = [&](const std::string& input, const std::string& where) {
        if (input.empty()) return;
        std::error_code ec;
        const fs::path resolved = fs::canonical(input, ec);
        for (const fs::path& p : {fs::absolute(input), resolved}) {
            const std::string name = p.filename().string();
            if (p.empty() || !(overwrite ? isRunOutputName(name) : runWrites(scene, name)))
                continue;
            if (!fs::equivalent(p.parent_path(), outDir, ec)) continue;
            throw Error(where,
                        "the run would overwrite its input " + input + " with its output " +
                            p.filename().string() + " in the output folder " + outDir,
                        "choose another --out folder (one that holds none of the scene's "
                        "inputs)");
        }
    };
    check(scene.path, scene.path);
    for (const GrainFileSpec& f : scene.grainFiles) check(f.file, f.where);
    for (const AssetSetSpec& set : scene.assetSets) check(set.catalog, set.where);
    for (const AssetSpec& a : scene.assets) {
        check(a.file, a.where);
        check(a.meshFile, a.where);
    }
}

/// Refuses a restart writing into @a outDir when its frames.pvd, which lists the frames
/// written before the checkpoint, would name files only the checkpoint's folder holds.
void refuseFramesAwayFromTheirSeries(const Scene& scene, const Checkpoint& checkpoint,
                                     const std::string& restartPath, const std::string& outDir)
{
    if (!(scene.output.vtkPeriod > 0.0) || checkpoint.record.vtkFrameTimes.empty()) return;
    const std::string checkpointDir = fs::absolute(restartPath).parent_path().string();
    std::error_code ec;
    if (fs::equivalent(checkpointDir, outDir, ec)) return;
    throw Error(outDir,
                "a restart continues the ParaView series of " + checkpointDir +
                    ": frames.pvd here would list " +
                    std::to_string(checkpoint.record.vtkFrameTimes.size()) +
                    " earlier frames that only that folder holds",
                "drop --out to continue in " + checkpointDir +
                    ", or copy that folder to " + outDir + " and restart from the copy's " +
                    kCheckpointFileName);
}

/// Refuses to go on in @a dir, which another run holds (FolderLock.h).
void refuseBusyFolder(const std::string& dir)
{
    throw Error(dir,
                "another run is still writing this folder (after a kill -9 of mpirun, its "
                "ranks run on for a while)",
                "wait for that run to end, or stop its lsdem-run processes, then try again");
}

} // namespace lsdem::runfolder
