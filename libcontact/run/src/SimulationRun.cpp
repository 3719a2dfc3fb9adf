#include "lsdem/run/SimulationRun.h"

#include "lsdem/ls/Stopwatch.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/RunOutputs.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/run/VtkSeries.h"
#include "lsdem/ls/AtomicFile.h"
#include "lsdem/ls/Error.h"
#include "lsdem/ls/Inspection.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>

namespace lsdem {

namespace {

std::atomic<bool> gStopRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "requestStop must be signal-safe");

/// Steps between outputs for a period in time units (at least one step).
long long stepsPer(double period, double dt)
{
    return std::max(1LL, static_cast<long long>(std::llround(period / dt)));
}

bool endReached(const Scene& scene, const World& w, double dt)
{
    const EndCondition& end = scene.end;
    if (end.steps > 0 && w.step >= end.steps) return true;
    if (end.time > 0.0 && w.time >= end.time - 1e-9 * dt) return true;
    if (end.boundary >= 0 &&
        w.boundaries[end.boundary].displacement.norm() >= end.displacement)
        return true;
    return false;
}

/// The number of steps the end condition implies (for progress), or -1 if unknown.
long long plannedSteps(const Scene& scene, const World& w, double dt)
{
    long long planned = -1;
    auto consider = [&](long long n) { planned = planned < 0 ? n : std::min(planned, n); };
    if (scene.end.steps > 0) consider(scene.end.steps);
    if (scene.end.time > 0.0) consider(static_cast<long long>(std::ceil(scene.end.time / dt - 1e-9)));
    if (scene.end.boundary >= 0) {
        const double speed = w.boundaries[scene.end.boundary].velocity.norm();
        if (speed > 0.0)
            consider(static_cast<long long>(std::ceil(scene.end.displacement / (speed * dt))));
    }
    return planned;
}

std::string formatDuration(double seconds)
{
    char buffer[32];
    if (seconds < 60) std::snprintf(buffer, sizeof buffer, "%.0fs", seconds);
    else if (seconds < 3600) std::snprintf(buffer, sizeof buffer, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
    else std::snprintf(buffer, sizeof buffer, "%dh%02dm", int(seconds) / 3600, (int(seconds) / 60) % 60);
    return buffer;
}

/// The ParaView output of a run: surfaces extracted once per asset, frames on demand.
class FrameWriter
{
public:
    FrameWriter(const std::string& dir, const World& world) : mSeries(dir, "frames")
    {
        // Surfaces at about the node spacing: as fine as the contact sees them, and light
        // enough for many grains and frames (at the level set's own voxels a frame of 27
        // spheres of 100 voxels across is 150 MB).
        for (const auto& asset : world.assets)
            if (!mSurfaces.count(asset.get()))
                mSurfaces[asset.get()] =
                    zeroIsosurface(*asset->levelSet, asset->spacing.mean);
    }
    VtkSeries& series() { return mSeries; }

    void write(const Simulation& sim)
    {
        const World& w = sim.world();
        std::vector<VtkGrain> grains;
        for (size_t i = 0; i < w.grains.size(); ++i) {
            const Grain& g = w.grains[i];
            grains.push_back({&mSurfaces.at(g.asset.get()), g.body.pose, static_cast<int>(i),
                              g.motion == GrainMotion::Fixed ? Vec3::Zero() : g.body.velocity,
                              g.angularVelocity()});
        }
        std::vector<VtkForcePoint> forces;
        for (const ContactForceRecord& f : sim.contactForces())
            forces.push_back({f.point, f.force, f.grain});
        mSeries.writeFrame(mSeries.framesWritten(), w.time, grains, forces);
    }

private:
    VtkSeries mSeries;
    std::map<const GrainAsset*, TriangleMesh> mSurfaces;
};

void printSummary(std::ostream& log, const RunResult& r)
{
    const StepCounters& c = r.counters;
    const double stepping = c.broadSeconds + c.narrowSeconds + c.integrateSeconds;
    char line[200];
    log << "\nwhere the time went:\n";
    auto row = [&](const char* name, double s) {
        std::snprintf(line, sizeof line, "  %-22s %10.3f s  %5.1f %%\n", name, s,
                      r.wallSeconds > 0 ? 100.0 * s / r.wallSeconds : 0.0);
        log << line;
    };
    row("setup (assets, scene)", r.setupSeconds);
    row("broad phase", c.broadSeconds);
    row("narrow phase + laws", c.narrowSeconds);
    row("integration", c.integrateSeconds);
    row("output", r.outputSeconds);
    row("total (wall)", r.wallSeconds);
    const double steps = static_cast<double>(c.steps);
    std::snprintf(line, sizeof line,
                  "throughput: %lld steps, %.3g ms/step, %.3g grain-steps/s, %.3g node checks/s "
                  "(%.1f %% culled before sampling)\n",
                  c.steps, steps > 0 ? 1e3 * stepping / steps : 0.0,
                  stepping > 0 ? steps * r.grains / stepping : 0.0,
                  c.narrowSeconds > 0 ? c.nodes.nodesConsidered / c.narrowSeconds : 0.0,
                  c.nodes.nodesConsidered > 0
                      ? 100.0 * double(c.nodes.nodesCulled) / double(c.nodes.nodesConsidered)
                      : 0.0);
    log << line;
}

} // namespace

void requestStop()
{
    gStopRequested.store(true);
}

RunResult runSimulation(const RunOptions& options, std::ostream& log)
{
    const auto wallStart = SteadyClock::now();
    RunResult result;
    gStopRequested.store(false);

    // The scene: from its file, or from the text kept in the checkpoint.
    const bool restart = !options.restartPath.empty();
    Checkpoint checkpoint;
    Scene scene;
    if (restart) {
        checkpoint = readCheckpoint(options.restartPath);
        scene = parseScene(checkpoint.sceneText, checkpoint.scenePath);
    } else {
        scene = readSceneFile(options.scenePath);
        checkpoint.scenePath = std::filesystem::absolute(options.scenePath).string();
        checkpoint.sceneText = scene.text;
    }
    std::string outDir = options.outDir;
    if (outDir.empty() && restart)
        outDir = std::filesystem::absolute(options.restartPath).parent_path().string();
    if (outDir.empty())
        throw Error("", "no output folder given", "pass --out DIR");

    std::vector<std::string> warnings;
    World world = buildWorld(scene, warnings);
    for (const std::string& w : warnings) log << "warning: " << w << "\n";
    prepareOutputFolder(outDir, "choose a writable --out folder");  // once the scene is good
    std::vector<Vec3> initialPositions;
    for (const Grain& g : world.grains) initialPositions.push_back(g.body.pose.position);

    double dt = scene.timeStep.fixed;
    if (restart) {
        dt = checkpoint.timeStep;
        restoreWorldState(options.restartPath, world);
    } else if (!(dt > 0.0)) {
        dt = automaticTimeStep(world, scene.timeStep.safety);
        log << "time step (auto, safety " << scene.timeStep.safety << "): " << dt << "\n";
    }
    const bool recordForces = scene.output.vtkPeriod > 0.0 && scene.output.contactForces;
    Simulation sim(std::move(world), dt, !restart, recordForces);
    RunRecord& record = checkpoint.record;
    checkpoint.timeStep = dt;
    result.timeStep = dt;
    result.grains = static_cast<int>(sim.world().grains.size());

    const OutputSpec& out = scene.output;
    const long long historyEvery =
        out.historyEvery > 0 ? out.historyEvery
        : out.historyPeriod > 0.0 ? stepsPer(out.historyPeriod, dt) : 100;
    const long long vtkEvery = out.vtkPeriod > 0.0 ? stepsPer(out.vtkPeriod, dt) : 0;
    const long long checkpointEvery =
        out.checkpointPeriod > 0.0 ? stepsPer(out.checkpointPeriod, dt) : 0;
    const std::string checkpointPath =
        (std::filesystem::path(outDir) / "checkpoint.lsdem").string();
    result.checkpointPath = checkpointPath;

    std::unique_ptr<FrameWriter> frames;
    if (vtkEvery > 0) {
        frames = std::make_unique<FrameWriter>(outDir, sim.world());
        frames->series().restoreFrameTimes(record.vtkFrameTimes);
    }
    auto writeTextOutputs = [&] {
        writeHistoryFiles(outDir, sim.world(), record);
        writeGrainsFile((std::filesystem::path(outDir) / "grains.csv").string(), sim.world(),
                        initialPositions);
    };
    auto writeCheckpoint = [&] {
        if (frames) record.vtkFrameTimes = frames->series().frameTimes();
        saveCheckpoint(checkpointPath, sim.world(), checkpoint);
        writeTextOutputs();
    };
    if (!restart) {
        recordHistoryRow(sim, record);
        if (frames) frames->write(sim);
    }
    result.setupSeconds = secondsSince(wallStart);

    const long long planned = plannedSteps(scene, sim.world(), dt);
    const long long firstStep = sim.world().step;
    auto lastFlush = SteadyClock::now(), lastProgress = SteadyClock::now();
    const auto loopStart = SteadyClock::now();
    while (!endReached(scene, sim.world(), dt)) {
        try {
            sim.step();
        } catch (const Error&) {
            writeTextOutputs();  // the history up to the failure helps to see what went wrong
            throw;
        }
        const long long step = sim.world().step;
        const auto outputStart = SteadyClock::now();
        if (step % historyEvery == 0) recordHistoryRow(sim, record);
        if (frames && step % vtkEvery == 0) frames->write(sim);
        const bool stop = gStopRequested.load() ||
                          (options.stopAtStep > 0 && step >= options.stopAtStep);
        if (stop || (checkpointEvery > 0 && step % checkpointEvery == 0)) {
            writeCheckpoint();
            lastFlush = SteadyClock::now();
        } else if (secondsSince(lastFlush) > 10.0) {  // keep the history files fresh
            writeTextOutputs();
            lastFlush = SteadyClock::now();
        }
        result.outputSeconds += secondsSince(outputStart);
        if (stop) {
            result.interrupted = true;
            break;
        }
        if (options.progress && secondsSince(lastProgress) > 0.5) {
            lastProgress = SteadyClock::now();
            const double elapsed = secondsSince(loopStart);
            const double perStep = elapsed / static_cast<double>(step - firstStep);
            char line[160];
            if (planned > 0)
                std::snprintf(line, sizeof line, "\rstep %lld/%lld  t = %.4g  %4.1f %%  ETA %s   ",
                              step, planned, sim.world().time, 100.0 * step / planned,
                              formatDuration(perStep * double(planned - step)).c_str());
            else
                std::snprintf(line, sizeof line, "\rstep %lld  t = %.4g   ", step,
                              sim.world().time);
            std::fputs(line, stderr);
        }
    }
    if (options.progress) std::fputs("\n", stderr);

    const auto finalStart = SteadyClock::now();
    if (!result.interrupted) {
        const World& w = sim.world();
        const bool rowWritten = !record.energyRows.empty() &&
                                record.energyRows.back()[0] == static_cast<double>(w.step);
        if (!rowWritten) recordHistoryRow(sim, record);
        if (frames && w.step % vtkEvery != 0) frames->write(sim);
        writeCheckpoint();
    }
    result.outputSeconds += secondsSince(finalStart);
    result.step = sim.world().step;
    result.time = sim.world().time;
    result.counters = sim.counters();
    result.wallSeconds = secondsSince(wallStart);
    if (result.interrupted)
        log << "stopped at step " << result.step << " (t = " << result.time
            << "); continue with: lsdem-run --restart " << checkpointPath << "\n";
    else
        log << "finished at step " << result.step << " (t = " << result.time << ")\n";
    printSummary(log, result);
    return result;
}

} // namespace lsdem
