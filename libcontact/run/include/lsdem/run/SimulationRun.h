/// @file SimulationRun.h
/// @brief A whole run, as lsdem-run performs it: read the scene (or a checkpoint), build the
///        world, choose the time step, step to the end condition while writing the history,
///        ParaView frames and checkpoints, stop cleanly on request (SIGINT/SIGTERM), and
///        report where the time went.
#pragma once

#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Simulation.h"

#include <iosfwd>
#include <string>

namespace lsdem {

struct RunOptions
{
    std::string scenePath;    ///< start from this scene file, or ...
    std::string restartPath;  ///< ... continue from this checkpoint
    std::string outDir;       ///< output folder ("" on restart: the checkpoint's folder)
    /// A fresh run refuses an outDir holding an earlier run's outputs (the two would mix);
    /// with overwrite, it removes them (those files only) once the scene is good.
    bool overwrite = false;
    bool progress = false;    ///< a progress line with ETA on stderr
    /// Stop (as if interrupted, with a checkpoint) once the step count reaches this (0: never).
    long long stopAtStep = 0;
    /// > 0: end at this time, or after this many steps in all, instead of the scene's end
    /// (or the checkpoint's). The checkpoints keep it, so a restart continues to it.
    double endTime = 0.0;
    long long endSteps = 0;
    /// Split the run by space over these ranks (GhostDecomposition.h), each of which calls
    /// runSimulation with the same options; rank 0 writes the histories, grains.csv and the
    /// checkpoints (gathered from the ranks), each rank its piece of every ParaView frame.
    /// Null: one process.
    RankGroup* ranks = nullptr;
    /// Worker threads of this process, for the header (0: not said).
    int threads = 0;
};

struct RunResult
{
    bool interrupted = false;   ///< stopped by a request or stopAtStep, not the end condition
    bool alreadyEnded = false;  ///< a restart whose checkpoint was at the end: nothing done
    long long step = 0;
    double time = 0.0;
    double timeStep = 0.0;
    std::string checkpointPath;
    StepCounters counters;
    double outputSeconds = 0.0, setupSeconds = 0.0, wallSeconds = 0.0;
    int grains = 0;
    int ranks = 1;                ///< processes the run was split over
    GhostCounters decomposition;  ///< this rank's, when split over ranks
};

/// Perform the run described by @a options; messages and the summary go to @a log.
/// @throw Error for bad scenes, bad checkpoints, an output folder holding an earlier run
///        (without overwrite), unwritable outputs or an unstable time step (outputs written
///        before the failure stay intact).
RunResult runSimulation(const RunOptions& options, std::ostream& log);

/// Ask a running runSimulation to stop after its current step, write a checkpoint and return.
/// Async-signal-safe (a lock-free atomic flag), so a signal handler may call it.
void requestStop();

} // namespace lsdem
