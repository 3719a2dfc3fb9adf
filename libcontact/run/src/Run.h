// The run in progress behind runSimulation (SimulationRun.h): the scene, the simulation and
// everything it writes. Set up in RunSetup.cpp; stepped and written in SimulationRun.cpp.
// Private to lsdem_run.
#pragma once

#include "FrameWriter.h"

#include "lsdem/core/FolderLock.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/SimulationRun.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Simulation.h"

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lsdem {

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
    // Setting up, in order (the constructor): the output folder (true: a restart in its
    // checkpoint's own folder), the scene (or the checkpoint's), the folder's rules (the
    // earlier run's outputs to replace), the simulation, the folder made and locked, the
    // output periods and the first history row and frame.
    bool chooseOutputFolder(const RunOptions& options);
    void readScene(const RunOptions& options, bool restartInPlace);
    std::vector<std::string> checkOutputFolder(const RunOptions& options, bool restartInPlace);
    /// @return the seconds of the first force evaluation (a step's cost, for estimates)
    double makeSimulation(const RunOptions& options);
    void prepareOutputs(const RunOptions& options, bool restartInPlace,
                        const std::vector<std::string>& earlier);
    void planOutputs(double firstEvaluationSeconds);
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
    /// Each grain's pose at the run's start (the scene's): grains.csv's displacements, the
    /// frames' micromechanics.
    std::vector<RigidPose> mStartPoses;
    Vec3 mStartCellSize = Vec3::Zero();  ///< a periodic cell's size at the start (its D²min's)
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

} // namespace lsdem
