// A whole run as lsdem-run performs it: start (from a scene or a checkpoint), step to the end
// condition while writing the outputs, finish (or stop cleanly on request) and report.
#include "lsdem/run/SimulationRun.h"

#include "FrameWriter.h"
#include "OutputFolder.h"
#include "Run.h"
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

} // namespace

const World& Run::wholeWorld(World& gathered)
{
    if (!mDecomposition) return mSim->world();
    gathered = mDecomposition->gatherWorld(mSim->world());
    return gathered;
}

void Run::writeFiles(const World& whole)
{
    writeHistoryFiles(mOutDir, whole, mCheckpoint.record);
    std::vector<Vec3> startPositions;
    for (const RigidPose& p : mStartPoses) startPositions.push_back(p.position);
    writeGrainsFile((fs::path(mOutDir) / kGrainsFileName).string(), whole, startPositions);
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

namespace {

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
