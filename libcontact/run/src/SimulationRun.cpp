// A whole run as lsdem-run performs it: start (from a scene or a checkpoint), step to the end
// condition while writing the outputs, finish (or stop cleanly on request) and report.
#include "lsdem/run/SimulationRun.h"

#include "FrameWriter.h"
#include "OutputFolder.h"
#include "RunPlan.h"
#include "RunSummary.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/FolderLock.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/RunOutputs.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <vector>

namespace lsdem {

namespace {

namespace fs = std::filesystem;
using namespace runplan;
using namespace runfolder;

std::atomic<bool> gStopRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "requestStop must be signal-safe");

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

/// A run in progress: the scene, the simulation and everything it writes.
class Run
{
public:
    Run(const RunOptions& options, std::ostream& log);

    /// Step until the end condition or a stop request; true if it stopped early.
    bool stepToEnd();
    /// Write the last history row, frame and the checkpoint (after a normal end).
    void finish();
    /// Whether a restart began where its run had already ended (nothing stepped or written).
    bool alreadyEnded() const { return mAlreadyEnded; }
    void fillResult(RunResult& result) const;

private:
    /// The histories, and unless @a withGrains is false grains.csv. Split over ranks it is
    /// collective (the grains are gathered to rank 0), unless @a withGrains is false.
    void writeTextOutputs(bool withGrains = true);
    /// The checkpoint and the text outputs (collective when split over ranks).
    void writeCheckpoint();
    /// The whole world: the simulation's own, or split over ranks, gathered from them into
    /// @a gathered on rank 0 (collective; the other ranks get no grains).
    const World& wholeWorld(World& gathered);
    void writeFiles(const World& whole);
    void printProgress();
    /// The run's end: the scene's, or the one its checkpoint kept, or the one @a options give
    /// (kept in this run's checkpoints).
    void applyEnd(const RunOptions& options);
    /// Whether to rewrite the text outputs now (10 s after the last time; split over ranks,
    /// decided together at history steps, since it gathers the grains).
    bool flushDue(long long step);
    /// The checkpoint to continue from, read once for the whole job (collective when split
    /// over ranks); continuing in its own folder, that folder stays locked for this run.
    Checkpoint readCheckpointToContinue(bool inPlace);

    const RunOptions& mOptions;
    std::ostream& mLog;
    Stopwatch mWall;
    bool mRestart = false;
    bool mAlreadyEnded = false;
    Scene mScene;
    Checkpoint mCheckpoint;
    std::string mOutDir, mCheckpointPath;
    /// The output folder, locked by the process that writes it for as long as the run lasts.
    FolderLock mOutLock;
    std::vector<Vec3> mInitialPositions;
    /// Split over ranks: this rank's part of the grains; only rank 0 writes.
    std::unique_ptr<GhostDecomposition> mDecomposition;
    bool mWrites = true;
    std::unique_ptr<Simulation> mSim;
    std::unique_ptr<FrameWriter> mFrames;
    long long mHistoryEvery = 0, mVtkEvery = 0, mCheckpointEvery = 0;
    double mPlannedSteps = -1.0;
    double mSetupSeconds = 0.0, mOutputSeconds = 0.0, mVoteSeconds = 0.0;
    long long mFirstStep = 0;
    Stopwatch mSinceFlush, mSinceProgress, mLoop;
};

Run::Run(const RunOptions& options, std::ostream& log) : mOptions(options), mLog(log)
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
    if (mRestart) refuseFramesAwayFromTheirSeries(mScene, mCheckpoint, options.restartPath, mOutDir);
    // Before any work, and before writing anything.
    refuseOutputsOverInputs(mScene, mOutDir, options.overwrite);
    const std::vector<std::string> earlier = [&] {
        if (restartInPlace) return std::vector<std::string>();
        const OutputFolderFiles found = scanOutputFolder(mOutDir, mScene);
        refuseEarlierRun(mOutDir, found, options.overwrite);
        return found.earlierRun;
    }();

    // One rank evaluates every contact: nothing to split, nothing to exchange.
    if (options.ranks && options.ranks->ranks() > 1)
        mDecomposition = std::make_unique<GhostDecomposition>(*options.ranks);
    std::vector<std::string> warnings;
    World world = buildWorld(mScene, warnings);
    for (const std::string& w : warnings) log << "warning: " << w << "\n";
    if (mWrites)  // for grains.csv's displacements
        for (const Grain& g : world.grains) mInitialPositions.push_back(g.body.pose.position);

    double dt = mScene.timeStep.fixed;
    if (mRestart) {
        dt = mCheckpoint.timeStep;
        restoreWorldState(mCheckpoint, options.restartPath, world);
        std::string().swap(mCheckpoint.fileBytes);  // the state is in the world now
    } else if (!(dt > 0.0)) {
        dt = automaticTimeStep(world, mScene.timeStep.safety);
        log << "time step (auto, safety " << mScene.timeStep.safety << "): " << dt << "\n";
    }
    const OutputSpec& out = mScene.output;
    const bool recordForces = out.vtkPeriod > 0.0 && out.contactForces;
    const Stopwatch firstEvaluation;
    mSim = mDecomposition ? std::make_unique<Simulation>(std::move(world), dt, !mRestart,
                                                         recordForces, *mDecomposition)
                          : std::make_unique<Simulation>(std::move(world), dt, !mRestart,
                                                         recordForces);
    mCheckpoint.timeStep = dt;
    mCheckpointPath = (fs::path(mOutDir) / kCheckpointFileName).string();
    // A restart from a run that had already reached its end adds nothing: its last frame and
    // checkpoint would only be written again (a second frame at the same time in frames.pvd).
    mAlreadyEnded = mRestart && endReached(mScene, mSim->world(), dt);
    if (mAlreadyEnded) {
        mCheckpointPath = options.restartPath;
        mFirstStep = mSim->world().step;
        return;
    }
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

    mPlannedSteps = plannedSteps(mScene, mSim->world(), dt);
    if (mPlannedSteps > 0.0) {
        // The first force evaluation stands in for a step: enough to tell minutes from years.
        const std::string warning =
            longRunWarning(mScene, mPlannedSteps, dt, firstEvaluation.seconds());
        if (!warning.empty()) log << "warning: " << warning << "\n";
    }

    mHistoryEvery = out.historyEvery > 0      ? out.historyEvery
                    : out.historyPeriod > 0.0 ? stepsPer(out.historyPeriod, dt)
                                              : 100;
    mVtkEvery = out.vtkPeriod > 0.0 ? stepsPer(out.vtkPeriod, dt) : 0;
    mCheckpointEvery = out.checkpointPeriod > 0.0 ? stepsPer(out.checkpointPeriod, dt) : 0;
    // Split over ranks, every rank writes its piece of each frame.
    if (mVtkEvery > 0 && (mWrites || mDecomposition)) {
        mFrames = std::make_unique<FrameWriter>(mOutDir, mSim->world());
        mFrames->series().restoreFrameTimes(mCheckpoint.record.vtkFrameTimes);
    }
    if (!mRestart) {
        recordHistoryRow(*mSim, mCheckpoint.record);
        if (mFrames) mFrames->write(*mSim);
    }
    mSetupSeconds = mWall.seconds();
    mFirstStep = mSim->world().step;
    mSinceFlush.restart();
    mSinceProgress.restart();
    mLoop.restart();
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

const World& Run::wholeWorld(World& gathered)
{
    if (!mDecomposition) return mSim->world();
    gathered = mDecomposition->gatherWorld(mSim->world());
    return gathered;
}

void Run::writeFiles(const World& whole)
{
    writeHistoryFiles(mOutDir, whole, mCheckpoint.record);
    writeGrainsFile((fs::path(mOutDir) / kGrainsFileName).string(), whole, mInitialPositions);
}

void Run::writeTextOutputs(bool withGrains)
{
    if (!withGrains) {  // the histories need only what every rank holds
        if (mWrites) writeHistoryFiles(mOutDir, mSim->world(), mCheckpoint.record);
        return;
    }
    World gathered;
    const World& whole = wholeWorld(gathered);
    if (mWrites) writeFiles(whole);
}

void Run::writeCheckpoint()
{
    World gathered;
    const World& whole = wholeWorld(gathered);
    if (!mWrites) return;
    if (mFrames) mCheckpoint.record.vtkFrameTimes = mFrames->series().frameTimes();
    // The histories first: a kill between the two leaves files a little ahead of the
    // checkpoint, never behind it (a restart rewrites them from the checkpoint's rows).
    writeFiles(whole);
    saveCheckpoint(mCheckpointPath, whole, mCheckpoint);
}

bool Run::stepToEnd()
{
    while (!endReached(mScene, mSim->world(), mSim->timeStep())) {
        try {
            mSim->step();
        } catch (const Error&) {
            // The history up to the failure helps to see what went wrong (split over ranks,
            // without grains.csv: gathering it would wait for ranks that may not have failed).
            writeTextOutputs(!mDecomposition);
            throw;
        }
        const long long step = mSim->world().step;
        // A signal may reach one rank only: the ranks stop together, at the same step. (The
        // vote waits for the slowest rank: exchange time.)
        const Stopwatch vote;
        const bool requested = mOptions.ranks ? mOptions.ranks->anyRank(gStopRequested.load())
                                              : gStopRequested.load();
        mVoteSeconds += vote.seconds();
        const Stopwatch output;
        if (step % mHistoryEvery == 0) recordHistoryRow(*mSim, mCheckpoint.record);
        if (mFrames && step % mVtkEvery == 0) mFrames->write(*mSim);
        // A stop on the last step is an end: finish() writes the last row and frame, which a
        // restart from this checkpoint would not (it has nothing left to step).
        const bool stop = (requested || (mOptions.stopAtStep > 0 && step >= mOptions.stopAtStep)) &&
                          !endReached(mScene, mSim->world(), mSim->timeStep());
        if (stop || (mCheckpointEvery > 0 && step % mCheckpointEvery == 0)) {
            writeCheckpoint();
            mSinceFlush.restart();
        } else if (flushDue(step)) {  // keep the history files fresh
            writeTextOutputs();
            mSinceFlush.restart();
        }
        mOutputSeconds += output.seconds();
        if (stop) return true;
        if (mOptions.progress && mSinceProgress.seconds() > 0.5) {
            mSinceProgress.restart();
            printProgress();
        }
    }
    return false;
}

bool Run::flushDue(long long step)
{
    const bool due = mSinceFlush.seconds() > 10.0;
    if (!mDecomposition) return due;
    return step % mHistoryEvery == 0 && mOptions.ranks->anyRank(due);
}

void Run::printProgress()
{
    const long long step = mSim->world().step;
    const double perStep = mLoop.seconds() / static_cast<double>(step - mFirstStep);
    char line[160];
    if (mPlannedSteps > 0.0)
        std::snprintf(line, sizeof line, "\rstep %lld/%.0f  t = %.4g  %4.1f %%  ETA %s   ", step,
                      mPlannedSteps, mSim->world().time, 100.0 * double(step) / mPlannedSteps,
                      formatDuration(perStep * (mPlannedSteps - double(step))).c_str());
    else
        std::snprintf(line, sizeof line, "\rstep %lld  t = %.4g   ", step, mSim->world().time);
    std::fputs(line, stderr);
}

void Run::finish()
{
    const Stopwatch output;
    const World& w = mSim->world();
    const std::vector<std::vector<double>>& rows = mCheckpoint.record.energyRows;
    const bool rowWritten = !rows.empty() && rows.back()[0] == static_cast<double>(w.step);
    if (!rowWritten) recordHistoryRow(*mSim, mCheckpoint.record);
    if (mFrames && w.step % mVtkEvery != 0) mFrames->write(*mSim);
    writeCheckpoint();
    mOutputSeconds += output.seconds();
}

void Run::fillResult(RunResult& result) const
{
    result.timeStep = mSim->timeStep();
    result.grains = mDecomposition ? mDecomposition->globalCount()
                                   : static_cast<int>(mSim->world().grains.size());
    result.checkpointPath = mCheckpointPath;
    result.setupSeconds = mSetupSeconds;
    result.outputSeconds = mOutputSeconds;
    result.step = mSim->world().step;
    result.time = mSim->world().time;
    result.counters = mSim->counters();
    result.wallSeconds = mWall.seconds();
    if (mOptions.ranks) result.ranks = mOptions.ranks->ranks();
    if (mDecomposition) {
        result.decomposition = mDecomposition->counters();
        result.decomposition.exchangeSeconds += mVoteSeconds;
    }
}

/// The header line saying what the run runs on (with threads or ranks given).
void printWhereItRuns(const RunOptions& options, std::ostream& log)
{
    if (options.ranks || options.threads > 0) {
        const int ranks = options.ranks ? options.ranks->ranks() : 1;
        log << "running on " << ranks
            << (!options.ranks ? " process" : ranks == 1 ? " rank" : " ranks");
        if (options.threads > 0)
            log << " x " << options.threads << (options.threads == 1 ? " thread" : " threads");
        log << (ranks > 1 ? " (split by space: each rank owns its sub-domain's grains, with "
                            "ghosts of its neighbours')\n"
                          : "\n");
    }
}

} // namespace

void requestStop()
{
    gStopRequested.store(true);
}

RunResult runSimulation(const RunOptions& options, std::ostream& log)
{
    gStopRequested.store(false);
    Run run(options, log);  // reads and checks everything first: a refused run says only why
    printWhereItRuns(options, log);
    RunResult result;
    if (run.alreadyEnded()) {
        run.fillResult(result);
        result.alreadyEnded = true;
        log << "the run had already finished at step " << result.step << " (t = " << result.time
            << "): nothing to continue, nothing written (to go further, give a later end: "
               "--end-time or --end-steps)\n";
        return result;
    }
    result.interrupted = run.stepToEnd();
    if (options.progress) std::fputs("\n", stderr);
    if (!result.interrupted) run.finish();
    run.fillResult(result);
    if (result.interrupted)
        log << "stopped at step " << result.step << " (t = " << result.time
            << "); continue with: lsdem-run --restart " << result.checkpointPath << "\n";
    else
        log << "finished at step " << result.step << " (t = " << result.time << ")\n";
    printRunSummary(log, result);
    return result;
}

} // namespace lsdem
