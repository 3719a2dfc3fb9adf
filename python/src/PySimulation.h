// The Simulation class of the Python module (private to python/src): a World built as
// lsdem-run builds it, stepped on its own TBB arena with the GIL released, the run's end
// and checkpoints as lsdem-run has them. SimulationBindings.cpp binds it, SimulationViews.cpp
// its grains and boundaries.
#pragma once

#include "Bindings.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/run/RunEnd.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "lsdem/simulation/Simulation.h"

#include <pybind11/stl.h>

#include <tbb/task_arena.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

namespace lsdem::python {

namespace fs = std::filesystem;


/// While C++ steps without a callback, Python gets the GIL back this often to notice Ctrl-C.
constexpr double kSignalCheckSeconds = 0.2;

inline void warnAll(const std::vector<std::string>& warnings)
{
    for (const std::string& w : warnings)
        if (PyErr_WarnEx(PyExc_UserWarning, ("lsdem: " + w).c_str(), 2) != 0)
            throw py::error_already_set();
}

class PySimulation
{
    /// Marks a run in progress (and by which thread) while it lasts. The flag is read and
    /// written with the GIL held, so Python threads see it in turn.
    class Running
    {
    public:
        explicit Running(PySimulation& sim) : mSim(sim)
        {
            if (sim.mRunning)
                throw Error("",
                            sim.mRunner == std::this_thread::get_id()
                                ? "run() was called from its own callback"
                                : "this simulation is busy in another thread (a run() or a "
                                  "checkpoint())",
                            "wait for it to return; one simulation does one thing at a time");
            sim.mRunning = true;
            sim.mRunner = std::this_thread::get_id();
        }
        ~Running() { mSim.mRunning = false; }
        Running(const Running&) = delete;
        Running& operator=(const Running&) = delete;

    private:
        PySimulation& mSim;
    };

public:
    /// A fresh start from @a scene, as lsdem-run starts one.
    PySimulation(const Scene& scene, std::optional<int> threads, bool recordContacts)
        : mScene(scene), mArena(makeArena(threads))
    {
        std::vector<std::string> warnings;
        {
            py::gil_scoped_release release;
            mArena->execute([&] {
                World world = buildWorld(mScene, warnings);
                double dt = mScene.timeStep.fixed;
                if (!(dt > 0.0)) dt = automaticTimeStep(world, mScene.timeStep.safety);
                mSim = std::make_unique<Simulation>(std::move(world), dt, true, recordContacts);
            });
        }
        warnAll(warnings);
    }

    /// Continue from a checkpoint written by checkpoint() or lsdem-run, as --restart does.
    PySimulation(const std::string& checkpointPath, std::optional<int> threads,
                 bool recordContacts)
        : mArena(makeArena(threads))
    {
        std::vector<std::string> warnings;
        {
            py::gil_scoped_release release;
            const Checkpoint c = readCheckpoint(checkpointPath);
            mScene = parseScene(c.sceneText, c.scenePath);
            applyCheckpointEnd(c, mScene, checkpointPath);  // the end the run had
            mRecord = c.record;
            mArena->execute([&] {
                World world = buildWorld(mScene, warnings);
                restoreWorldState(c, checkpointPath, world);  // the same reading as c
                mSim = std::make_unique<Simulation>(std::move(world), c.timeStep, false,
                                                    recordContacts);
            });
        }
        warnAll(warnings);
    }

    bool hasEndCondition() const
    {
        return mScene.end.time > 0.0 || mScene.end.steps > 0 || mScene.end.boundary >= 0;
    }
    bool done() const
    {
        return hasEndCondition() && endReached(mScene, mSim->world(), mSim->timeStep());
    }

    /// Step @a steps times, or to the end condition; call @a callback(self) after each step.
    long long run(const py::object& self, std::optional<long long> steps,
                  const py::object& callback)
    {
        if (steps && *steps < 0) throw Error("", "steps must be >= 0");
        const Running running(*this);
        if (!steps && !hasEndCondition())
            throw Error("", "the scene has no end condition, so run() would never stop",
                        "pass steps=N, or set scene.end_time / scene.end_steps");
        long long done = 0;
        auto more = [&] { return steps ? done < *steps : !this->done(); };
        if (callback.is_none()) {
            bool finished = false;
            while (!finished) {
                {
                    py::gil_scoped_release release;
                    const Stopwatch slice;
                    mArena->execute([&] {
                        while (more() && slice.seconds() < kSignalCheckSeconds) {
                            mSim->step();
                            ++done;
                        }
                    });
                    finished = !more();
                }
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            }
        } else {
            while (more()) {
                {
                    py::gil_scoped_release release;
                    mArena->execute([&] { mSim->step(); });
                }
                ++done;
                callback(self);
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            }
        }
        return done;
    }

    /// Refuse to read the world from another thread while it steps (its arrays of point
    /// forces are rebuilt at every step). Its own callback may read it.
    void checkNotSteppingElsewhere() const
    {
        if (mRunning && mRunner != std::this_thread::get_id())
            throw Error("", "this simulation is stepping in another thread",
                        "read it from run()'s callback, or after run() returns");
    }

    void checkpoint(const std::string& path)
    {
        checkNotSteppingElsewhere();
        // Busy while the file is written (the GIL is released then), unless this is a run's
        // own callback, which already holds the simulation.
        std::optional<Running> writing;
        if (!mRunning) writing.emplace(*this);
        if (mScene.text.empty() && !hasEndCondition())
            throw Error("", "a checkpoint of a scene built in Python needs the scene's end "
                            "condition: lsdem-run and from_checkpoint read its scene as a file, "
                            "which must say when to stop",
                        "set scene.end_steps or scene.end_time before making the Simulation");
        Checkpoint c;
        if (!mScene.text.empty()) {
            c.scenePath = fs::absolute(mScene.path).string();
            c.sceneText = mScene.text;
        } else {
            // A scene built in Python: its TOML (assets must be files), read back on restart
            // from the folder its relative paths start from.
            const std::string folder =
                mScene.directory.empty() ? fs::current_path().string() : mScene.directory;
            c.sceneText = sceneToToml(withSavedAssetFiles(mScene), folder, "built in Python");
            c.scenePath = (fs::path(folder) / "python-scene.toml").string();
        }
        c.timeStep = mSim->timeStep();
        if (hasEndCondition()) c.end = mScene.end;  // as the run has it
        // The histories this simulation was restarted with (lsdem-run writes them out again
        // on --restart; steps taken in Python add no rows), or none, with one (empty) list
        // per boundary as a run's record has.
        c.record = mRecord;
        c.record.boundaryRows.resize(mSim->world().boundaries.size());
        py::gil_scoped_release release;
        saveCheckpoint(path, mSim->world(), c);
    }

    const Scene& scene() const { return mScene; }
    const Simulation& sim() const { return *mSim; }
    const World& world() const { return mSim->world(); }
    int threads() const { return mArena->max_concurrency(); }

private:
    Scene mScene;
    std::unique_ptr<tbb::task_arena> mArena;
    std::unique_ptr<Simulation> mSim;
    RunRecord mRecord;  ///< the histories of the checkpoint it continues (empty otherwise)
    bool mRunning = false;
    std::thread::id mRunner;
};

/// sim.grains: the grains' state; kept-alive views of the running world where the data is
/// stored as such, copies where it is computed.
struct GrainsView
{
    py::object owner;  ///< the Simulation
    const World& world() const { return owner.cast<const PySimulation&>().world(); }
    /// A view of the member at @a member of every grain (vectors are sizeof(Grain) apart).
    py::array vectors(const Vec3& (*member)(const Grain&)) const
    {
        const std::vector<Grain>& g = world().grains;
        return vectorView(g.empty() ? nullptr : &member(g.front()), g.size(), sizeof(Grain),
                          owner);
    }
};

struct BoundaryView
{
    py::object owner;
    int index = 0;
    const Boundary& boundary() const
    {
        return owner.cast<const PySimulation&>().world().boundaries[static_cast<size_t>(index)];
    }
};

struct BoundariesView
{
    py::object owner;
    const std::vector<Boundary>& all() const
    {
        return owner.cast<const PySimulation&>().world().boundaries;
    }
    BoundaryView at(const std::string& name) const
    {
        std::string known;
        for (size_t i = 0; i < all().size(); ++i) {
            if (all()[i].name == name) return {owner, static_cast<int>(i)};
            known += (known.empty() ? "'" : ", '") + all()[i].name + "'";
        }
        throw py::key_error("no boundary called '" + name + "'" +
                            (known.empty() ? std::string(" (the scene has none)")
                                           : "; the scene has " + known));
    }
};

struct MembraneView
{
    py::object owner;
    int index = 0;
    const Membrane& membrane() const
    {
        return owner.cast<const PySimulation&>().world().membranes[static_cast<size_t>(index)];
    }
};

/// sim.membranes: by name, as sim.boundaries.
struct MembranesView
{
    py::object owner;
    const std::vector<Membrane>& all() const
    {
        return owner.cast<const PySimulation&>().world().membranes;
    }
    MembraneView at(const std::string& name) const
    {
        for (size_t i = 0; i < all().size(); ++i)
            if (all()[i].name == name) return {owner, static_cast<int>(i)};
        throw py::key_error("no membrane called '" + name + "'");
    }
};

/// The Membrane and Membranes classes of sim.membranes (MembraneViews.cpp).
void bindMembraneViews(py::module_& m);

/// The Grains, Boundary and Boundaries classes of sim.grains and sim.boundaries
/// (SimulationViews.cpp).
void bindSimulationViews(py::module_& m);

} // namespace lsdem::python
