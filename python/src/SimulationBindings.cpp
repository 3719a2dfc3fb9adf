// Simulations in Python: the same world, time step, stepping and end check as lsdem-run (so
// the same numbers, bit for bit), on a TBB arena of the requested size, with the GIL released
// while C++ steps. Grain state comes out as numpy views into the running world.
#include "PySimulation.h"

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

// Long by nature: one .def per method and property of Simulation, in the order help() lists them.
void bindSimulation(py::module_& m)
{
    bindSimulationViews(m);
    bindMembraneViews(m);
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
        .def_property_readonly(
            "periodic_cell",
            [](const PySimulation& s) -> py::object {
                const PeriodicCell& c = s.world().periodic;
                if (!c.active()) return py::none();
                const auto triple = [](const Vec3& v) {
                    return py::array_t<double>(py::ssize_t{3}, v.data());
                };
                py::dict d;
                d["origin"] = triple(c.origin);
                d["size"] = triple(c.size);
                d["strain_rate"] = triple(c.strainRate);
                d["stress"] = triple(c.stress);
                return std::move(d);
            },
            "None, or in a periodic cell a dict of copies (3,): origin, size (its periods now), "
            "strain_rate (1/time) and stress (compressive positive, measured while it deforms).")
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
                d["dissipated_friction"] = e.friction;
                d["dissipated_dashpot"] = e.dashpot;
                d["dissipated_global_damping"] = e.globalDamping;
                return d;
            },
            "The energy balance now: kinetic, elastic, potential, boundary_work, dissipated (what "
            "the balance leaves), and that split by mechanism: dissipated_friction, "
            "dissipated_dashpot, dissipated_global_damping (what they leave of it is the "
            "integrator's error).")
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
            "membranes", [](py::object self) { return MembranesView{self}; },
            "The membranes by name: sim.membranes['sleeve'].volume.")
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
