// Setting up a run (Run.h): its output folder and the folder's rules, the scene or the
// checkpoint it continues, the simulation, and the outputs' periods and first rows.
#include "Run.h"

#include "OutputFolder.h"
#include "RunPlan.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/run/RunOutputs.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include "lsdem/core/NumberText.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <limits>

namespace lsdem {

namespace {

namespace fs = std::filesystem;
using namespace runplan;
using namespace runfolder;

/// Rank 0's @a bytes on every rank of @a ranks (collective).
std::string fromRankZero(RankGroup& ranks, const std::string& bytes)
{
    std::vector<char> mine;
    if (ranks.isRoot()) mine.assign(bytes.begin(), bytes.end());
    std::vector<char> all;
    std::vector<size_t> starts;
    ranks.allGather(mine, all, starts);
    return std::string(all.data() + starts[0], starts[1] - starts[0]);
}

} // namespace

Run::Run(const RunOptions& options, std::ostream& log) : mOptions(options), mLog(log)
{
    const bool restartInPlace = chooseOutputFolder(options);
    readScene(options, restartInPlace);
    // Before any work, and before writing anything.
    const std::vector<std::string> earlier = checkOutputFolder(options, restartInPlace);
    const double firstEvaluationSeconds = makeSimulation(options);
    // A restart from a run that had already reached its end adds nothing: its last frame and
    // checkpoint would only be written again (a second frame at the same time in frames.pvd).
    mAlreadyEnded = mRestart && endReached(mScene, mSim->world(), mSim->timeStep());
    if (mAlreadyEnded) {
        mCheckpointPath = options.restartPath;
        mFirstStep = mSim->world().step;
        return;
    }
    prepareOutputs(options, restartInPlace, earlier);
    planOutputs(firstEvaluationSeconds);
    mSetupSeconds = mWall.seconds();
    mFirstStep = mSim->world().step;
    mSinceFlush.restart();
    mSinceProgress.restart();
    mLoop.restart();
}

bool Run::chooseOutputFolder(const RunOptions& options)
{
    mRestart = !options.restartPath.empty();
    mOutDir = options.outDir;
    if (mOutDir.empty() && mRestart)
        mOutDir = fs::absolute(options.restartPath).parent_path().string();
    if (mOutDir.empty()) throw Error("", "no output folder given", "pass --out DIR");
    // A restart in its own folder continues the outputs there; elsewhere it starts a folder of
    // its own, as a fresh run does.
    std::error_code ec;
    const bool restartInPlace =
        mRestart &&
        fs::equivalent(fs::absolute(options.restartPath).parent_path(), mOutDir, ec);
    if (restartInPlace && options.overwrite)
        throw Error("", "--overwrite with --restart in the checkpoint's own folder: a restart "
                        "continues the outputs there, it replaces none",
                    "drop --overwrite");
    if (options.ranks) mWrites = options.ranks->isRoot();
    mCheckpointPath = (fs::path(mOutDir) / kCheckpointFileName).string();
    return restartInPlace;
}

void Run::readScene(const RunOptions& options, bool restartInPlace)
{
    // The scene: from its file, or from the text kept in the checkpoint.
    if (mRestart) {
        mCheckpoint = readCheckpointToContinue(restartInPlace);
        mScene = parseScene(mCheckpoint.sceneText, mCheckpoint.scenePath);
    } else {
        mScene = readSceneFile(options.scenePath);
        mCheckpoint.scenePath = fs::absolute(options.scenePath).string();
        mCheckpoint.sceneText = mScene.text;
    }
    applyEnd(options);
}

std::vector<std::string> Run::checkOutputFolder(const RunOptions& options, bool restartInPlace)
{
    if (mRestart) refuseFramesAwayFromTheirSeries(mScene, mCheckpoint, options.restartPath, mOutDir);
    refuseOutputsOverInputs(mScene, mOutDir, options.overwrite);
    if (restartInPlace) return {};
    const OutputFolderFiles found = scanOutputFolder(mOutDir, mScene);
    refuseEarlierRun(mOutDir, found, options.overwrite);
    return found.earlierRun;
}

namespace {

/// A frame_spacing as large as a grain would draw no surface for it: the grain would vanish
/// from the frames.
void refuseFrameSpacingBeyondGrains(const Scene& scene, const World& world)
{
    const double spacing = scene.output.frameSpacing;
    if (!(spacing > 0.0) || scene.output.vtkPeriod <= 0.0) return;
    double smallest = std::numeric_limits<double>::infinity();
    for (const auto& asset : world.assets) smallest = std::min(smallest, asset->boundingRadius);
    if (spacing > smallest)
        throw Error(scene.path,
                    "[output] frame_spacing " + numberText(spacing) +
                        " is more than the smallest grain's bounding radius " +
                        numberText(smallest) + ": that grain would vanish from the frames",
                    "give at most half a grain's radius (about 200 triangles a grain), or 0");
}

} // namespace

double Run::makeSimulation(const RunOptions& options)
{
    // One rank evaluates every contact: nothing to split, nothing to exchange.
    if (options.ranks && options.ranks->ranks() > 1) {
        mDecomposition = std::make_unique<GhostDecomposition>(*options.ranks);
    }
    std::vector<std::string> warnings;
    World world = buildWorld(mScene, warnings);
    for (const std::string& w : warnings) mLog << "warning: " << w << "\n";
    refuseFrameSpacingBeyondGrains(mScene, world);
    if (mWrites)  // for grains.csv's displacements and the frames' micromechanics
        for (const Grain& g : world.grains) mStartPoses.push_back(g.body.pose);
    mStartCellSize = world.periodic.size;

    double dt = mScene.timeStep.fixed;
    if (mRestart) {
        dt = mCheckpoint.timeStep;
        restoreWorldState(mCheckpoint, options.restartPath, world);
        std::string().swap(mCheckpoint.fileBytes);  // the state is in the world now
    } else if (!(dt > 0.0)) {
        dt = automaticTimeStep(world, mScene.timeStep.safety);
        mLog << "time step (auto, safety " << mScene.timeStep.safety << "): " << dt << "\n";
    }
    const OutputSpec& out = mScene.output;
    const bool recordForces = out.vtkPeriod > 0.0 && out.contactForces;
    const Stopwatch firstEvaluation;
    mSim = mDecomposition ? std::make_unique<Simulation>(std::move(world), dt, !mRestart,
                                                         recordForces, *mDecomposition)
                          : std::make_unique<Simulation>(std::move(world), dt, !mRestart,
                                                         recordForces);
    mCheckpoint.timeStep = dt;
    return firstEvaluation.seconds();
}

void Run::prepareOutputs(const RunOptions& options, bool restartInPlace,
                         const std::vector<std::string>& earlier)
{
    // Only now, with the scene, the checkpoint's body and the first forces found good, is the
    // folder made (bad input leaves none behind); split over ranks, the others wait for it
    // before writing their pieces of the first frame.
    // (Only rank 0 can fail here; the vote tells the others, which would otherwise wait.)
    std::exception_ptr notPrepared;
    if (mWrites) {
        try {
            prepareOutputFolder(mOutDir, "choose a writable --out folder");
            // A restart in place holds this lock since it read its checkpoint.
            if (!restartInPlace && !mOutLock.tryLock(mOutDir, FolderLock::Mode::Exclusive))
                refuseBusyFolder(mOutDir);
            removeEarlierRun(mOutDir, earlier);  // --overwrite: the folder holds this run only
        } catch (...) {
            notPrepared = std::current_exception();
        }
    }
    const bool anyFailed = options.ranks ? options.ranks->anyRank(bool(notPrepared)) : false;
    if (notPrepared) std::rethrow_exception(notPrepared);
    if (anyFailed)
        throw Error(mOutDir, "rank 0 could not prepare the output folder",
                    "see rank 0's message");
}

void Run::planOutputs(double firstEvaluationSeconds)
{
    const double dt = mSim->timeStep();
    mPlannedSteps = plannedSteps(mScene, mSim->world(), dt);
    if (mPlannedSteps > 0.0) {
        // The first force evaluation stands in for a step: enough to tell minutes from years.
        const std::string warning =
            longRunWarning(mScene, mPlannedSteps, dt, firstEvaluationSeconds);
        if (!warning.empty()) mLog << "warning: " << warning << "\n";
    }
    const OutputSpec& out = mScene.output;
    mHistoryEvery = out.historyEvery > 0      ? out.historyEvery
                    : out.historyPeriod > 0.0 ? stepsPer(out.historyPeriod, dt)
                                              : 100;
    mVtkEvery = out.vtkPeriod > 0.0 ? stepsPer(out.vtkPeriod, dt) : 0;
    mCheckpointEvery = out.checkpointPeriod > 0.0 ? stepsPer(out.checkpointPeriod, dt) : 0;
    // Split over ranks, every rank writes its piece of each frame.
    if (mVtkEvery > 0 && (mWrites || mDecomposition)) {
        mFrames = std::make_unique<FrameWriter>(
            mOutDir, mSim->world(), out.micromechanics ? &mStartPoses : nullptr, out.frameSpacing,
            mStartCellSize);
        mFrames->series().restoreFrameTimes(mCheckpoint.record.vtkFrameTimes);
    }
    mCheckpoint.record.micromechanics = out.micromechanics;
    if (!mRestart) {
        recordHistoryRow(*mSim, mCheckpoint.record);
        if (mFrames) mFrames->write(*mSim);
    }
}

void Run::applyEnd(const RunOptions& options)
{
    if (mRestart) applyCheckpointEnd(mCheckpoint, mScene, options.restartPath);
    if (options.endTime > 0.0 || options.endSteps > 0) {
        mScene.end = EndCondition();
        mScene.end.time = options.endTime;
        mScene.end.steps = options.endSteps;
        mCheckpoint.end = mScene.end;
    }
}

Checkpoint Run::readCheckpointToContinue(bool inPlace)
{
    // Rank 0 alone reads the file, once: the ranks must all continue the same checkpoint, and
    // its history rows and its state must come from one version of the file. The lock keeps
    // a run still writing that folder (its checkpoint replaced meanwhile) from being read.
    const std::string& path = mOptions.restartPath;
    Checkpoint checkpoint;
    std::exception_ptr notRead;
    if (mWrites) {
        try {
            const std::string folder = fs::absolute(path).parent_path().string();
            FolderLock reading;
            FolderLock& lock = inPlace ? mOutLock : reading;
            if (!lock.tryLock(folder, inPlace ? FolderLock::Mode::Exclusive
                                              : FolderLock::Mode::Shared))
                refuseBusyFolder(folder);
            checkpoint = readCheckpoint(path);
        } catch (...) {
            notRead = std::current_exception();
        }
    }
    RankGroup* ranks = mOptions.ranks;
    const bool anyFailed = ranks ? ranks->anyRank(bool(notRead)) : false;
    if (notRead) std::rethrow_exception(notRead);
    if (anyFailed)
        throw Error(path, "rank 0 could not read the checkpoint", "see rank 0's message");
    if (ranks && ranks->ranks() > 1) {
        const std::string bytes = fromRankZero(*ranks, checkpoint.fileBytes);
        if (!ranks->isRoot()) checkpoint = parseCheckpoint(bytes, path);
    }
    return checkpoint;
}

} // namespace lsdem
