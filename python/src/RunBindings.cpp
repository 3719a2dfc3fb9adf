// Whole runs from Python, as the programs perform them: lsdem.run_scene is lsdem-run (the
// same output files, byte for byte), lsdem.study.two_spheres is `lsdem-study two-spheres`
// returning its rows. The GIL is released while C++ works.
#include "Bindings.h"

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/NormalModel.h"
#include "lsdem/core/Error.h"
#include "lsdem/run/SimulationRun.h"
#include "studies/TwoSpheresStudy.h"

#include <pybind11/stl.h>

#include <tbb/task_arena.h>

#include <filesystem>
#include <optional>
#include <sstream>

namespace lsdem::python {

namespace {

/// A path given as str or os.PathLike.
std::string pathText(const py::handle& path)
{
    return py::str(py::module_::import("os").attr("fspath")(path));
}

py::dict runScene(const py::object& scene, const py::object& out, std::optional<int> threads,
                  bool progress, long long stopAtStep, bool overwrite)
{
    RunOptions options;
    options.scenePath = pathText(scene);
    options.outDir = pathText(out);
    options.progress = progress;
    options.overwrite = overwrite;
    if (stopAtStep < 0) throw Error("", "stop_at_step wants a number >= 0 (0: run to the end)");
    options.stopAtStep = stopAtStep;
    const std::unique_ptr<tbb::task_arena> arena = makeArena(threads);
    std::ostringstream log;
    RunResult result;
    {
        py::gil_scoped_release release;
        arena->execute([&] { result = runSimulation(options, log); });
    }
    py::dict d;
    d["interrupted"] = result.interrupted;
    d["step"] = result.step;
    d["time"] = result.time;
    d["time_step"] = result.timeStep;
    d["checkpoint"] = result.checkpointPath;
    d["grains"] = result.grains;
    d["wall_seconds"] = result.wallSeconds;
    d["log"] = log.str();
    return d;
}

std::vector<Formulation> parseFormulations(const std::vector<std::string>& names)
{
    if (names.empty()) throw Error("", "formulations is empty", "name at least one, e.g. [\"adapted\"]");
    std::vector<Formulation> list;
    for (const std::string& name : names) list.push_back(parseFormulation(name));
    return list;
}

py::list twoSpheres(const std::vector<std::string>& formulations, const std::vector<int>& nodes,
                    const std::vector<double>& stiffnessFactors, int kSeriesNodes, double radius,
                    double voxel, double deltaMax, int steps, int orientations, unsigned seed,
                    const std::string& testing, const std::optional<py::object>& outDir,
                    std::optional<int> threads)
{
    TwoSpheresOptions o;
    o.formulations = parseFormulations(formulations);
    o.nodeCounts = nodes;
    o.stiffnessFactors = stiffnessFactors;
    o.kSeriesNodes = kSeriesNodes;
    o.radius = radius;
    o.voxel = voxel;
    o.deltaMax = deltaMax;
    o.steps = steps;
    o.orientations = orientations;
    o.seed = seed;
    o.testing = parseNodeTesting(testing);
    o.plots = false;
    o.quiet = true;
    checkTwoSpheresOptions(o);
    const std::string csvPath =
        outDir ? (std::filesystem::path(pathText(*outDir)) / "two_spheres.csv").string() : "";
    const std::unique_ptr<tbb::task_arena> arena = makeArena(threads);
    TwoSpheresResult result;
    {
        py::gil_scoped_release release;
        arena->execute([&] {
            result = runTwoSpheres(o);
            if (!csvPath.empty()) {
                std::filesystem::create_directories(std::filesystem::path(csvPath).parent_path());
                writeTwoSpheresCsv(result, o, csvPath);
            }
        });
    }
    py::list rows;
    for (const TwoSpheresRow& r : result.rows) {
        py::dict row;
        row["formulation"] = formulationName(r.formulation);
        row["nodes"] = r.nodesRequested;
        row["nodes_actual"] = static_cast<long long>(r.nodesActual);
        row["stiffness"] = r.stiffness;
        row["delta"] = r.delta;
        row["force"] = r.forceMean;
        row["force_std"] = r.forceStd;
        row["force_min"] = r.forceMin;
        row["force_max"] = r.forceMax;
        row["force_exact"] = r.forceExact;
        rows.append(row);
    }
    return rows;
}

} // namespace

void bindRuns(py::module_& m)
{
    m.def("run_scene", &runScene, py::arg("scene"), py::arg("out"), py::arg("threads") = py::none(),
          py::arg("progress") = false, py::arg("stop_at_step") = 0, py::arg("overwrite") = false,
          "Run the scene file `scene` exactly as `lsdem-run scene --out out` does: the same\n"
          "output files in folder `out` (energy.csv, boundary_<name>.csv, grains.csv, ParaView\n"
          "frames, checkpoints as the scene asks), the same numbers bit for bit, on `threads`\n"
          "threads (default: all cores). stop_at_step > 0 stops there with a checkpoint.\n"
          "A folder holding an earlier run's outputs is refused, unless overwrite=True\n"
          "(lsdem-run --overwrite): then those files (and no others) are removed first.\n"
          "Returns a dict: step, time, time_step, grains, interrupted, checkpoint (path),\n"
          "wall_seconds and log (the summary lsdem-run prints). Raises lsdem.Error on a bad\n"
          "scene, an earlier run in `out`, an unwritable folder or an unstable time step (files\n"
          "already written stay).");

    py::module_ study = m.def_submodule(
        "study", "The paper's studies as functions returning their rows (lists of dicts).");
    const TwoSpheresOptions defaults;
    study.def("two_spheres", &twoSpheres,
              py::arg("formulations") = std::vector<std::string>{"original", "adapted"},
              py::arg("nodes") = defaults.nodeCounts,
              py::arg("stiffness_factors") = defaults.stiffnessFactors,
              py::arg("k_series_nodes") = defaults.kSeriesNodes,
              py::arg("radius") = defaults.radius, py::arg("voxel") = defaults.voxel,
              py::arg("delta_max") = defaults.deltaMax, py::arg("steps") = defaults.steps,
              py::arg("orientations") = defaults.orientations, py::arg("seed") = defaults.seed,
              py::arg("testing") = nodeTestingName(defaults.testing),
              py::arg("out_dir") = py::none(), py::arg("threads") = py::none(),
              "The two-sphere central-compression study of `lsdem-study two-spheres` (Feldfogel\n"
              "et al. 2024, Fig. 1 and 3): two spheres of `radius` baked at `voxel` with about\n"
              "each of `nodes` surface nodes, one pressed into the other by 0 ... delta_max in\n"
              "`steps` steps, the force averaged over `orientations` random orientations, for\n"
              "each formulation ('original', 'adapted', 'single-node', 'volume') at its paper\n"
              "stiffness; at the node count nearest k_series_nodes also at stiffness_factors\n"
              "times it. Lengths in the sphere's unit (mm in the paper), forces in N.\n"
              "Returns one dict per row: formulation, nodes, nodes_actual, stiffness, delta,\n"
              "force (mean), force_std, force_min, force_max and force_exact (the adapted\n"
              "formulation's continuum limit for that stiffness, about pi kn* R delta^2 / 2). With\n"
              "out_dir, also writes out_dir/two_spheres.csv as lsdem-study does (no plots).");
}

} // namespace lsdem::python
