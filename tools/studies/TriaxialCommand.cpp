#include "studies/TriaxialCommand.h"

#include "studies/RunDistributor.h"
#include "studies/StudyCommandOptions.h"
#include "studies/ThreadLimit.h"
#include "studies/TriaxialCost.h"
#include "studies/TriaxialOutputs.h"
#include "studies/TriaxialShearScene.h"
#include "studies/TriaxialStudy.h"

#include "common/CommandLine.h"
#include "common/PlotScripts.h"
#include "common/StudyOutput.h"

#include "lsdem/core/Stopwatch.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace lsdem {

namespace {

/// What the study writes into --out: its CSVs, triaxial.py's plots and the shearing scene
/// (its assets: removeEarlierSceneAssets).
const cli::StudyFiles kOwnFiles = {"triaxial.csv", "triaxial_runs.csv",
                                   "triaxial_convergence.csv", "triaxial_curves.png",
                                   "triaxial_friction_angles.png", "scene/triaxial_shear.toml",
                                   "scene/grains.csv", "scene/membrane_state.csv"};

/// Remove the assets in DIR/scene/assets that an earlier run's shear scene names (they are
/// named after its meshes, so a rerun with other meshes would leave them beside the new ones);
/// any other file there is the user's and is kept; how many went is printed unless @a quiet.
/// Call before that scene is removed.
void removeEarlierSceneAssets(const std::string& outDir, bool quiet)
{
    namespace fs = std::filesystem;
    std::ifstream in(fs::path(outDir) / "scene" / "triaxial_shear.toml");
    if (!in) return;
    std::ostringstream text;
    text << in.rdbuf();
    const std::string scene = text.str();
    std::error_code ec;
    int removed = 0;
    for (const fs::directory_entry& e :
         fs::directory_iterator(fs::path(outDir) / "scene" / "assets", ec)) {
        std::error_code typeError;
        if (!e.is_regular_file(typeError) || e.path().extension() != ".vdb") continue;
        const std::string named = "assets/" + e.path().filename().string();
        if (scene.find("'" + named + "'") == std::string::npos &&
            scene.find('"' + named + '"') == std::string::npos)
            continue;
        cli::removeEarlierRunFile(e.path().string());
        ++removed;
    }
    if (removed > 0 && !quiet)
        std::printf("removed %d asset%s of an earlier run's scene from %s/scene/assets\n", removed,
                    removed == 1 ? "" : "s", outDir.c_str());
}

} // namespace

// Long by nature: one entry per option, in the order --help lists them.
TriaxialCommand::TriaxialCommand(CLI::App& study)
    : mCommand(study.add_subcommand(
          "triaxial",
          "Triaxial compression of a granular sample, adapted against original\n\n"
          "A sample of --grains grains (the meshes of --meshes, in turn, on a loose lattice, "
          "random\norientations) in a cuboid of six walls: consolidated isotropically to "
          "--confining-stress\nby servo walls, then loaded along --path (by default compressed "
          "axially at the strain\nrate of --inertial-number with the side walls holding the "
          "confining stress) to\n--axial-strain. Once per formulation and node\nspacing (SDP), at one voxel size "
          "(VDP): q, p, strains, void ratio, coordination; peak and\ncritical-state friction "
          "angles (docs/triaxial.md)."))
{
    using cli::addInteger;
    using cli::addNumber;
    using cli::addNumbers;
    TriaxialOptions& o = mOptions;
    const std::string sample = "Sample";
    cli::addTexts(*mCommand, "--meshes", o.meshes, "grain mesh files, or folders of them")
        ->type_name("PATH")
        ->group(sample);
    addInteger(*mCommand, "--grains", o.grains, "grains in the sample")->type_name("N")->group(sample);
    cli::addIntegers(*mCommand, "--seed", o.seeds,
                     "random seeds, one sample each (which mesh, orientation): every run is\n"
                     "made on each, and the summary gives their means")
        ->type_name("S")
        ->group(sample);
    addNumber(*mCommand, "--lattice-spacing", o.latticeSpacing,
              "spacing of the starting lattice, mm (0: 2.2 x the largest bounding radius at the "
              "coarsest SDP)")
        ->type_name("L")
        ->group(sample);
    addNumber(*mCommand, "--height-ratio", o.heightRatio,
              "the starting lattice's height over its width (2: a tall sample)")
        ->type_name("H")
        ->group(sample);
    addNumber(*mCommand, "--density", o.density, "grain density, tonne/mm^3")->type_name("RHO")->group(sample);
    const std::string resolution = "Resolution";
    addNumber(*mCommand, "--vdp", o.vdp, "voxel size, mm (every run)")->type_name("V")->group(resolution);
    addNumbers(*mCommand, "--sdps", o.sdps, "node spacings, mm, coarsest first")
        ->type_name("S")
        ->group(resolution);
    addFormulationOption(*mCommand, o.formulations)->group(resolution);
    const std::string law = "Contact law";
    addNumber(*mCommand, "--kn-star", o.knStar, "adapted kn*, N/mm^3")->type_name("K")->group(law);
    addNumber(*mCommand, "--kn-original", o.knOriginal,
              "original kn, N/mm (0: kn* x mean node area at the coarsest SDP)")
        ->type_name("K")
        ->group(law);
    addNumber(*mCommand, "--shear-ratio", o.shearRatio, "ks/kn")->type_name("R")->group(law);
    addNumber(*mCommand, "--friction", o.friction, "grain-grain friction while shearing")
        ->type_name("MU")
        ->group(law);
    addNumber(*mCommand, "--consolidation-friction", o.consolidationFriction,
              "grain-grain friction while consolidating (0: a dense sample)")
        ->type_name("MU")
        ->group(law);
    addNumber(*mCommand, "--wall-friction", o.wallFriction, "grain-wall friction")
        ->type_name("MU")
        ->group(law);
    addNumber(*mCommand, "--damping", o.globalDamping, "global damping")->type_name("L")->group(law);
    const std::string test = "Test";
    addNumber(*mCommand, "--confining-stress", o.confiningStress, "sigma_3, MPa")
        ->type_name("S")
        ->group(test);
    addNumber(*mCommand, "--inertial-number", o.inertialNumber,
              "I = rate x d x sqrt(rho/sigma_3): sets the axial strain rate")
        ->type_name("I")
        ->group(test);
    addNumber(*mCommand, "--axial-strain", o.maxAxialStrain, "axial strain at the end")
        ->type_name("E")
        ->group(test);
    std::string pathNames;
    for (TriaxialPath path : allTriaxialPaths())
        pathNames += (pathNames.empty() ? "" : ", ") + triaxialPathName(path);
    mCommand
        ->add_option_function<std::string>(
            "--path",
            [&o](const std::string& name) {
                const std::optional<TriaxialPath> path = triaxialPathNamed(name);
                if (!path) throw CLI::ValidationError("--path", "no loading path '" + name + "'");
                o.path = *path;
            },
            "the loading path after consolidation: " + pathNames +
                "\n(docs/triaxial.md#loading-paths)")
        ->type_name("PATH")
        ->default_str(triaxialPathName(o.path))
        ->group(test);
    mCommand
        ->add_option_function<std::string>(
            "--boundary",
            [&o](const std::string& name) {
                o.periodic = name == "periodic";
                o.membrane = name == "membrane";
            },
            "what bounds the sample: walls (six servo walls), periodic (a periodic cell, "
            "no walls) or membrane (a latex membrane round a cylinder cut from the sample "
            "consolidated between walls, the top and bottom walls its platens)")
        ->check(CLI::IsMember({"walls", "periodic", "membrane"}))
        ->type_name("B")
        ->default_str("walls")
        ->group(test);
    addNumber(*mCommand, "--membrane-youngs", o.membraneYoungs,
              "membrane: E of its rubber, MPa (latex about 1.4)")
        ->type_name("E")
        ->group(test);
    addNumber(*mCommand, "--membrane-thickness", o.membraneThickness,
              "membrane: its thickness, mm (0: half the grains' mean diameter; "
              "docs/triaxial.md#a-membrane-instead-of-side-walls)")
        ->type_name("T")
        ->group(test);
    addNumber(*mCommand, "--b", o.b, "true-triaxial: b = (sigma_2 - sigma_3)/(sigma_1 - sigma_3)")
        ->type_name("B")
        ->group(test);
    addNumber(*mCommand, "--unload-strain", o.unloadStrain,
              "unload-reload: the axial strain where unloading starts (0: half --axial-strain)")
        ->type_name("E")
        ->group(test);
    cli::addInteger(*mCommand, "--cycles", o.cycles,
                    "cyclic: strain cycles 0 -> +A -> -A -> 0, A = --axial-strain")
        ->type_name("N")
        ->group(test);
    addNumber(*mCommand, "--stress-tolerance", o.stressTolerance,
              "consolidated when every |sigma_i/sigma_3 - 1| is below this")
        ->type_name("T")
        ->group(test);
    const std::string output = "Output";
    addNumber(*mCommand, "--scene-strain", o.sceneStrain,
              "the axial strain the shear scene for lsdem-run goes to (0: --axial-strain's)")
        ->type_name("E")
        ->group(output);
    addInteger(*mCommand, "--records", o.records,
               "rows per run over the shearing: one every floor(steps/N) steps and one at\n"
               "the end (N to 2N-1 rows)")
        ->type_name("N")
        ->group(output);
    cli::addThreads(*mCommand, o.threads, "worker threads (default: all cores)")->group(output);
    addOutputOptions(*mCommand, o.outDir, o.plots, o.quiet, "print only the summary");
    mCommand->add_flag("--estimate", o.estimateOnly, "print the cost of the runs and stop")
        ->group(output);
    mCommand->footer("Units: mm, tonne, s, N (stresses in MPa). Writes DIR/triaxial.csv (rows of "
                     "every run),\nDIR/triaxial_runs.csv (one row per run) and, with "
                     "python3-matplotlib, DIR/*.png.");
}

bool TriaxialCommand::chosen() const
{
    return mCommand->parsed();
}

namespace {

/// The sample, a table of the runs, the seeds' means and the change between the two finest SDPs.
void printTriaxialSummary(const TriaxialOptions& o, const TriaxialStudyResult& result)
{
    const bool seeds = o.seeds.size() > 1;
    std::printf("sample: %lld grains of %d meshes (equivalent diameter %.3g mm), lattice "
                "spacing %.17g mm\n",
                result.grains, result.meshes, result.meanDiameter, result.spacing);
    std::printf("%-9s %6s %5s %6s %7s %6s %8s %7s %8s %7s %8s %9s %8s %8s %8s\n", "formul.",
                "SDP", "seed", "nodes", "e0", "Z0", "E50 MPa", "phi_pk", "eps_pk", "phi_cs", "e_cs",
                "I_max", "steps", "ms/step", "wall s");
    for (const TriaxialRun& r : result.runs) {
        const TriaxialTestResult& t = r.test;
        std::printf("%-9s %6.3g %5lld %6.0f %7.3f %6.2f %8.2f %7.2f %7.3f %8.2f %7.3f %9.2e %8lld "
                    "%8.2f %8.0f%s\n",
                    formulationName(r.formulation).c_str(), r.sdp, r.seed, r.nodesPerGrain,
                    t.consolidated.voidRatio, t.consolidated.coordination, t.secantModulus50,
                    t.peakFrictionAngle,
                    t.peakAxialStrain, t.criticalFrictionAngle, t.criticalVoidRatio,
                    t.maxInertialNumber, t.consolidationSteps + t.shearSteps, r.msPerStep,
                    r.runSeconds, t.consolidatedWithinTolerance ? "" : "  (not consolidated)");
    }
    if (seeds)
        for (const TriaxialSeedMean& m : triaxialSeedMeans(result))
            std::printf("%s SDP %g, mean of %d seeds (standard deviation): peak friction angle "
                        "%.2f (%.2f) deg, E50 %.2f (%.2f) MPa\n",
                        formulationName(m.formulation).c_str(), m.sdp, m.seeds,
                        m.peakFrictionAngle, m.peakFrictionAngleSpread, m.secantModulus50,
                        m.secantModulus50Spread);
    // Successive SDPs seed by seed (the same samples at both): the change and its standard
    // error, beside how many nodes the mean contact held.
    for (const TriaxialPairedChange& c : triaxialPairedChanges(result))
        std::printf("%s SDP %g -> %g, paired over %d seed%s: peak friction angle %+.2f deg "
                    "(standard error %.2f), E50 %+.1f %% (%.1f); nodes per contact %.1f -> %.1f\n",
                    formulationName(c.formulation).c_str(), c.coarseSdp, c.fineSdp, c.seeds,
                    c.seeds == 1 ? "" : "s", c.peakFrictionAngle, c.peakFrictionAngleError,
                    100.0 * c.secantModulus50, 100.0 * c.secantModulus50Error,
                    c.coarseNodesPerContact, c.fineNodesPerContact);
    for (Formulation f : o.formulations) {
        const double change = finestPeakChange(result, f);
        if (std::isfinite(change))
            std::printf("%s, between the two finest SDPs%s: peak friction angle %+.2f deg, "
                        "E50 %+.1f %%\n",
                        formulationName(f).c_str(), seeds ? " (means over the seeds)" : "",
                        change, 100.0 * finestModulusChange(result, f));
    }
}

} // namespace

int TriaxialCommand::run(RunDistributor& ranks) const
{
    const TriaxialOptions& o = mOptions;
    checkTriaxialOptions(o);
    const ThreadLimit threads(o.threads, ranks);
    if (!ranks.isRoot()) {
        runTriaxialStudy(o, ranks);
        return 0;
    }
    cli::checkOutputFolder(o.outDir);  // made once the runs are done: --meshes is read by them
    if (ranks.ranks() > 1) std::printf("%s\n", describeRanks(ranks, threads).c_str());
    std::printf("triaxial: %lld grains, sigma_3 = %g MPa, I = %g, to %g %% axial strain, "
                "VDP %g mm\n",
                o.grains, o.confiningStress, o.inertialNumber, 100.0 * o.maxAxialStrain, o.vdp);
    std::fflush(stdout);

    const Stopwatch wall;
    // A run is named by its formulation and SDP, and by its seed when there are several.
    const bool seeds = o.seeds.size() > 1;
    auto runName = [&](Formulation f, double sdp, long long seed) {
        char text[64];
        std::snprintf(text, sizeof text, "%s SDP %g", formulationName(f).c_str(), sdp);
        return seeds ? std::string(text) + " seed " + std::to_string(seed) : std::string(text);
    };
    auto onRun = [&](const TriaxialRun& r) {
        if (o.quiet) return;
        std::printf("  done: %s: %.0f nodes/grain, peak phi %.2f deg, critical phi "
                    "%.2f deg, %.0f s (shearing %.0f s, estimated %.0f s)\n",
                    runName(r.formulation, r.sdp, r.seed).c_str(), r.nodesPerGrain,
                    r.test.peakFrictionAngle, r.test.criticalFrictionAngle, r.runSeconds,
                    r.test.shearSeconds, r.test.shearSecondsEstimate);
        std::fflush(stdout);
    };
    int shearingRows = 0;
    auto progress = [&](Formulation f, double sdp, long long seed, const TriaxialRow& row) {
        if (o.quiet) return;
        if (row.shearSecondsEstimate >= 0.0)
            std::printf("  %s: consolidated at step %lld; the shearing, at the consolidation's "
                        "last pace: about %.0f s\n",
                        runName(f, sdp, seed).c_str(), row.step, row.shearSecondsEstimate);
        if (row.stage == 1 && ++shearingRows % 20 != 0) return;  // every tenth of the shearing
        std::printf("  %s: %s step %lld, eps_a %.3f, p %.4g, q %.4g, e %.3f\n",
                    runName(f, sdp, seed).c_str(),
                    row.stage == 0 ? "consolidating" : "shearing", row.step, row.axialStrain,
                    row.state.p, row.state.q, row.state.voidRatio);
        std::fflush(stdout);
    };
    // The estimate, with the threads each run gets (all cores unless --threads says fewer).
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    const int threadsPerRun =
        threads.threads() > 0 ? int(std::min<long long>(threads.threads(), cores)) : cores;
    auto onPlan = [&](const std::vector<TriaxialRunPlan>& plans) {
        if (o.quiet && !o.estimateOnly) return;
        std::printf("%s", describeTriaxialCost(plans, threadsPerRun, ranks.ranks()).c_str());
        if (o.membrane && !plans.empty()) {  // (docs/triaxial.md#cost)
            const TriaxialRunCost c = triaxialRunCost(plans.front(), threadsPerRun);
            std::printf("  (in the membrane: about %.0f of the %lld grains, %.0f of them next to "
                        "it, for its consolidation, about %lld steps, and the shearing; the most "
                        "if the shearing's step is halved)\n",
                        c.keptGrains, o.grains, c.grainsAtMembrane, c.membraneSteps);
        }
        std::fflush(stdout);
    };
    const TriaxialStudyResult result = runTriaxialStudy(o, ranks, onRun, progress, onPlan);
    if (o.estimateOnly) return 0;
    removeEarlierSceneAssets(o.outDir, o.quiet);
    cli::prepareOutputFolder(o.outDir, kOwnFiles, o.quiet);
    const std::string csv = o.outDir + "/triaxial.csv";
    const std::string runsCsv = o.outDir + "/triaxial_runs.csv";
    writeTriaxialCsv(result, csv);
    writeTriaxialRunsCsv(result, runsCsv);
    const std::string convergenceCsv = o.outDir + "/triaxial_convergence.csv";
    writeTriaxialConvergenceCsv(result, convergenceCsv);

    printTriaxialSummary(o, result);
    // The first formulation's finest run (of the first seed), as a scene to rerun the
    // shearing with lsdem-run (ParaView frames, wall histories) or to edit.
    const TriaxialRun* finest = nullptr;
    for (const TriaxialRun& r : result.runs)
        if (r.formulation == o.formulations.front() && (!finest || r.sdp < finest->sdp)) finest = &r;
    std::printf("time %.0f s\nwrote %s, %s, %s\n", wall.seconds(), csv.c_str(), runsCsv.c_str(),
                convergenceCsv.c_str());
    if (o.path == TriaxialPath::Compression || o.path == TriaxialPath::Extension) {
        const std::string scene = writeTriaxialShearScene(o, result, *finest, o.outDir + "/scene");
        std::printf("wrote %s: the shearing of %s for lsdem-run (ParaView frames)\n",
                    scene.c_str(), runName(finest->formulation, finest->sdp, finest->seed).c_str());
    } else {
        std::printf("no scene for lsdem-run: a scene's servo walls and cell hold fixed "
                    "stresses, and --path %s sets them as it goes\n",
                    triaxialPathName(o.path).c_str());
    }
    return o.plots ? cli::drawPlots("triaxial.py", {csv, runsCsv, o.outDir}) : 0;
}

} // namespace lsdem
