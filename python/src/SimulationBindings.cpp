// Simulations in Python: the same world, time step, stepping and end check as lsdem-run (so
// the same numbers, bit for bit), on a TBB arena of the requested size, with the GIL released
// while C++ steps. Grain state comes out as numpy views into the running world.
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

void checkThreads(std::optional<int> threads)
{
    // (TBB accepts far more, but an arena of 100000 threads crashes the interpreter at exit.)
    if (threads && (*threads < 1 || *threads > kMaxThreads))
        throw Error("", "threads wants a number from 1 to " + std::to_string(kMaxThreads) +
                            ", got " + std::to_string(*threads),
                    "leave it out for all cores");
}

std::unique_ptr<tbb::task_arena> makeArena(std::optional<int> threads)
{
    checkThreads(threads);
    return threads ? std::make_unique<tbb::task_arena>(*threads)
                   : std::make_unique<tbb::task_arena>();
}

namespace {

namespace fs = std::filesystem;

/// While C++ steps without a callback, Python gets the GIL back this often to notice Ctrl-C.
constexpr double kSignalCheckSeconds = 0.2;

void warnAll(const std::vector<std::string>& warnings)
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

const char* shapeName(BoundaryShape s)
{
    switch (s) {
    case BoundaryShape::Plane: return "plane";
    case BoundaryShape::Sphere: return "sphere";
    case BoundaryShape::LevelSet: return "level-set";
    case BoundaryShape::Cylinder: return "cylinder";
    case BoundaryShape::Orifice: return "orifice";
    }
    return "?";
}

void bindViews(py::module_& m)
{
    py::class_<GrainsView>(
        m, "Grains",
        "The grains of a running simulation, in scene order. positions, velocities, forces "
        "and torques are read-only numpy views into the simulation (no copy; they follow it "
        "as it steps and keep it alive); the other arrays are fresh copies.")
        .def("__len__", [](const GrainsView& g) { return g.world().grains.size(); })
        .def_property_readonly("names",
                               [](const GrainsView& g) {
                                   std::vector<std::string> names;
                                   for (const Grain& grain : g.world().grains)
                                       names.push_back(grain.name);
                                   return names;
                               })
        .def_property_readonly(
            "positions",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.body.pose.position; });
            },
            "(N, 3) float64 view: centroid positions (length).")
        .def_property_readonly(
            "velocities",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.body.velocity; });
            },
            "(N, 3) float64 view: centroid velocities (length/time).")
        .def_property_readonly(
            "forces",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.force; });
            },
            "(N, 3) float64 view: total force on each grain at the last evaluation.")
        .def_property_readonly(
            "torques",
            [](const GrainsView& g) {
                return g.vectors([](const Grain& x) -> const Vec3& { return x.torque; });
            },
            "(N, 3) float64 view: torque about each centroid at the last evaluation.")
        .def_property_readonly(
            "orientations",
            [](const GrainsView& g) {
                const std::vector<Grain>& grains = g.world().grains;
                py::array_t<double> out({static_cast<py::ssize_t>(grains.size()), py::ssize_t{4}});
                auto o = out.mutable_unchecked<2>();
                for (size_t i = 0; i < grains.size(); ++i) {
                    const Quat& q = grains[i].body.pose.orientation;
                    const auto r = static_cast<py::ssize_t>(i);
                    o(r, 0) = q.w(), o(r, 1) = q.x(), o(r, 2) = q.y(), o(r, 3) = q.z();
                }
                return out;
            },
            "(N, 4) float64 copy: unit quaternions [w, x, y, z], asset frame to world.")
        .def_property_readonly(
            "angular_velocities",
            [](const GrainsView& g) {
                std::vector<Vec3> omega;
                for (const Grain& grain : g.world().grains) omega.push_back(grain.angularVelocity());
                return vectorCopy(omega);
            },
            "(N, 3) float64 copy: world angular velocities (rad/time).")
        .def_property_readonly(
            "masses",
            [](const GrainsView& g) {
                const std::vector<Grain>& grains = g.world().grains;
                py::array_t<double> out(static_cast<py::ssize_t>(grains.size()));
                for (size_t i = 0; i < grains.size(); ++i)
                    out.mutable_at(static_cast<py::ssize_t>(i)) = grains[i].body.mass;
                return out;
            },
            "(N,) float64 copy: masses.");

    py::class_<BoundaryView>(m, "Boundary",
                             "One boundary of a running simulation (a wall, an indenter or a "
                             "level-set obstacle); values are copies taken when read.")
        .def_property_readonly("name", [](const BoundaryView& b) { return b.boundary().name; })
        .def_property_readonly("shape",
                               [](const BoundaryView& b) { return shapeName(b.boundary().shape); },
                               "'plane', 'sphere', 'cylinder' or 'level-set'.")
        .def_property_readonly("reaction",
                               [](const BoundaryView& b) { return toArray(b.boundary().force); },
                               "(3,) the grains' force on it at the last evaluation.")
        .def_property_readonly(
            "displacement", [](const BoundaryView& b) { return toArray(b.boundary().displacement); },
            "(3,) how far it has moved.")
        .def_property_readonly("velocity",
                               [](const BoundaryView& b) { return toArray(b.boundary().velocity); },
                               "(3,) its prescribed velocity.")
        .def_property_readonly(
            "position", [](const BoundaryView& b) { return toArray(b.boundary().referencePoint()); },
            "(3,) its reference point now (plane point, sphere centre, obstacle centroid).")
        .def("__repr__", [](const BoundaryView& b) {
            return std::string("<lsdem.Boundary '") + b.boundary().name + "' (" +
                   shapeName(b.boundary().shape) + ")>";
        });

    py::class_<BoundariesView>(m, "Boundaries",
                               "The boundaries of a running simulation, by name: "
                               "sim.boundaries['top'].reaction.")
        .def("__len__", [](const BoundariesView& b) { return b.all().size(); })
        .def("__getitem__", &BoundariesView::at, py::arg("name"))
        .def("__contains__",
             [](const BoundariesView& b, const std::string& name) {
                 for (const Boundary& x : b.all())
                     if (x.name == name) return true;
                 return false;
             })
        .def("keys",
             [](const BoundariesView& b) {
                 std::vector<std::string> names;
                 for (const Boundary& x : b.all()) names.push_back(x.name);
                 return names;
             },
             "The boundary names, in scene order.")
        .def("__iter__", [](const BoundariesView& b) {
            return py::iter(py::cast(b).attr("keys")());
        });
}

} // namespace

void bindSimulation(py::module_& m)
{
    bindViews(m);
    py::class_<PySimulation>(
        m, "Simulation",
        "A running simulation of a Scene: the world lsdem-run builds, the same time step "
        "(fixed, or automatic from the stiffest contact) and the same steps, so the numbers "
        "equal lsdem-run's bit for bit, for any thread count.\n\n"
        "    sim = lsdem.Simulation(scene, threads=2)\n"
        "    sim.run()                                     # to the scene's end condition\n"
        "    sim.run(steps=1000, callback=lsdem.every(100, lambda s: print(s.time)))\n"
        "    sim.grains.positions                          # (N, 3) numpy view\n"
        "    sim.boundaries['top'].reaction                # (3,)\n"
        "    sim.checkpoint('c.lsdem')                     # lsdem-run --restart reads it\n\n"
        "C++ steps with the GIL released; Ctrl-C stops a run between steps "
        "(KeyboardInterrupt). Bad scenes and unstable steps raise lsdem.Error.")
        .def(py::init<const Scene&, std::optional<int>, bool>(), py::arg("scene"),
             py::kw_only(), py::arg("threads") = py::none(), py::arg("record_contacts") = true,
             "Build the world of `scene` (loading or baking its assets), choose the time step "
             "and evaluate the initial forces. threads: TBB worker threads (default: all "
             "cores; results do not depend on it). record_contacts: keep the point forces of "
             "each step for sim.contacts (costs a little time and memory).")
        .def_static(
            "from_checkpoint",
            [](const std::string& path, std::optional<int> threads, bool recordContacts) {
                return std::make_unique<PySimulation>(path, threads, recordContacts);
            },
            py::arg("path"), py::kw_only(), py::arg("threads") = py::none(),
            py::arg("record_contacts") = true,
            "Continue from a checkpoint (written by checkpoint() or lsdem-run), "
            "bit-identically.")
        .def(
            "run",
            [](py::object self, std::optional<long long> steps, const py::object& callback) {
                return self.cast<PySimulation&>().run(self, steps, callback);
            },
            py::arg("steps") = py::none(), py::arg("callback") = py::none(),
            "Step to the scene's end condition, or `steps` times (whatever the end "
            "condition). callback(sim), if given, is called after every step (wrap it in "
            "lsdem.every(n, f) to call f every n steps). Returns the number of steps taken.")
        .def("checkpoint", &PySimulation::checkpoint, py::arg("path"),
             "Write a checkpoint (atomically): Simulation.from_checkpoint and lsdem-run "
             "--restart continue from it bit-identically. A scene built in Python is stored as "
             "its TOML, so its assets must have been saved to files (Asset.save, before or "
             "after scene.add_asset). The histories of the checkpoint it was restarted from "
             "are kept in it; steps run in Python add no rows to them.")
        .def_property_readonly("done",
                               [](const PySimulation& s) {
                                   s.checkNotSteppingElsewhere();
                                   return s.done();
                               },
                               "Whether the scene's end condition has been met.")
        .def_property_readonly("time", [](const PySimulation& s) { return s.world().time; },
                               "Simulated time.")
        .def_property_readonly("step", [](const PySimulation& s) { return s.world().step; },
                               "Steps taken since the start (a restart continues the count).")
        .def_property_readonly("time_step",
                               [](const PySimulation& s) { return s.sim().timeStep(); })
        .def_property_readonly("threads", &PySimulation::threads,
                               "The TBB threads it steps on.")
        .def_property_readonly("kinetic_energy",
                               [](const PySimulation& s) {
                                   s.checkNotSteppingElsewhere();
                                   return s.sim().energies().kinetic;
                               },
                               "Translational plus rotational kinetic energy (force·length).")
        .def_property_readonly(
            "energies",
            [](const PySimulation& s) {
                s.checkNotSteppingElsewhere();
                const Energies e = s.sim().energies();
                py::dict d;
                d["kinetic"] = e.kinetic;
                d["elastic"] = e.elastic;
                d["potential"] = e.potential;
                d["boundary_work"] = e.boundaryWork;
                d["dissipated"] = e.dissipated;
                return d;
            },
            "The energy balance now: kinetic, elastic, potential, boundary_work, dissipated.")
        .def_property_readonly("scene", &PySimulation::scene, py::return_value_policy::copy,
                               "A copy of the scene it runs.")
        .def_property_readonly(
            "grains", [](py::object self) { return GrainsView{self}; },
            "The grains: .positions, .velocities, .forces, .torques (views), .orientations, "
            ".angular_velocities, .masses, .names.")
        .def_property_readonly(
            "boundaries", [](py::object self) { return BoundariesView{self}; },
            "The boundaries by name: sim.boundaries['top'].reaction.")
        .def_property_readonly(
            "contacts",
            [](const PySimulation& s) {
                s.checkNotSteppingElsewhere();
                const std::vector<ContactForceRecord>& forces = s.sim().contactForces();
                const auto n = static_cast<py::ssize_t>(forces.size());
                py::array_t<double> points({n, py::ssize_t{3}}), values({n, py::ssize_t{3}});
                py::array_t<int> grains(n);
                auto p = points.mutable_unchecked<2>();
                auto f = values.mutable_unchecked<2>();
                for (py::ssize_t i = 0; i < n; ++i) {
                    const ContactForceRecord& r = forces[static_cast<size_t>(i)];
                    for (int k = 0; k < 3; ++k) p(i, k) = r.point[k], f(i, k) = r.force[k];
                    grains.mutable_at(i) = r.grain;
                }
                py::dict d;
                d["points"] = points;
                d["forces"] = values;
                d["grains"] = grains;
                return py::module_::import("types").attr("SimpleNamespace")(**d);
            },
            "The point forces of the last evaluation (copies; empty unless record_contacts): "
            ".points (M, 3) where they act, .forces (M, 3) on grain .grains (M,) int32. A "
            "boundary's reaction is not listed (see boundaries).")
        .def("__repr__", [](const PySimulation& s) {
            std::ostringstream text;
            text << "<lsdem.Simulation '" << s.scene().path << "': "
                 << s.world().grains.size() << " grains, step " << s.world().step
                 << ", t = " << s.world().time << ", dt = " << s.sim().timeStep() << ">";
            return text.str();
        });
}

} // namespace lsdem::python
