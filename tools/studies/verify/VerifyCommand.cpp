#include "studies/verify/VerifyCommand.h"

#include "studies/verify/VerifyCost.h"

#include "studies/RunDistributor.h"
#include "studies/StudyCommandOptions.h"
#include "studies/ThreadLimit.h"

#include "common/CommandLine.h"
#include "common/PlotScripts.h"
#include "common/StudyOutput.h"

#include "lsdem/ls/Inspection.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/run/VtkSeries.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <map>

namespace lsdem {

namespace {

const cli::StudyFiles kOwnFiles = {"verify_checks.csv", "verify_*.csv", "verify_*.png",
                                   "silo_spheres_frames/frames*", "silo_sand_frames/frames*"};

/// The spacing of a grain's surface in the frames: half its bounding radius (about 200 triangles
/// a grain), enough to see each shape; at the node spacing 4300 grains take 150 MB a frame.
double frameSpacing(const GrainAsset& asset)
{
    return std::max(asset.spacing.mean, 0.5 * asset.boundingRadius);
}

/// The frames of @a series as a ParaView series in `<dir>/<name>_frames`: each asset's surface
/// at its node spacing, posed.
void writeFrames(const verify::FrameSeries& series, const std::string& dir)
{
    const std::string folder = dir + "/" + series.name + "_frames";
    std::filesystem::create_directories(folder);
    VtkSeries vtk(folder, "frames");
    std::map<const GrainAsset*, TriangleMesh> surfaces;
    for (size_t k = 0; k < series.frames.size(); ++k) {
        const verify::VerifyFrame& frame = series.frames[k];
        std::vector<VtkGrain> grains;
        for (size_t i = 0; i < frame.grains.size(); ++i) {
            const GrainAsset* asset = frame.grains[i].asset.get();
            auto found = surfaces.find(asset);
            if (found == surfaces.end())
                found = surfaces.emplace(asset, zeroIsosurface(*asset->levelSet, frameSpacing(*asset)))
                            .first;
            grains.push_back({&found->second, frame.grains[i].pose, int(i), Vec3::Zero(), Vec3::Zero()});
        }
        vtk.writeFrame(int(k), frame.time, grains, {});
    }
}

std::string caseHelp()
{
    std::string text = "the cases to run (default: all but those run only when named):";
    for (const verify::CaseEntry& e : verify::caseList()) text += "\n  " + e.name + ": " + e.title;
    return text;
}

} // namespace

VerifyCommand::VerifyCommand(CLI::App& study)
    : mCommand(study.add_subcommand(
          "verify",
          "The verification suite: lsdem against published and exact references\n\n"
          "Single contacts and single bodies against theory, as a reviewer checks a DEM code\n"
          "before trusting it: the eight impact tests of Chung & Ooi (Granular Matter 13,\n"
          "2011) with references derived for lsdem's laws, slide-to-roll and rolling, blocks\n"
          "sliding and landing, free rotation, convergence with the node count, and a silo\n"
          "emptied through four orifices against Beverloo's law. A table of reference,\n"
          "lsdem, error, tolerance and pass; CSV, figures and the silo's ParaView frames in\n"
          "--out."))
{
    verify::VerifyOptions& o = mOptions;
    cli::addTexts(*mCommand, "--case", o.cases, caseHelp())->type_name("NAME");
    addFormulationOption(*mCommand, o.formulations);
    const std::string bodies = "Bodies and law (mm, t, s, N)";
    cli::addInteger(*mCommand, "--nodes", o.setup.sphereNodes, "nodes of the ball (about)")
        ->type_name("N")
        ->group(bodies);
    cli::addNumber(*mCommand, "--voxel", o.setup.sphereVoxel, "voxel of the ball's level set, mm")
        ->type_name("V")
        ->group(bodies);
    mCommand->add_option("--sand-meshes", o.sandMeshes, "the folder of the silo's sand grain meshes (.obj)")
        ->capture_default_str()
        ->type_name("DIR")
        ->group(bodies);
    mCommand->add_option("--silo-grains", o.siloGrains, "the silo's grains: spheres, sand")
        ->capture_default_str()
        ->check(CLI::IsMember({"spheres", "sand"}))
        ->type_name("KIND")
        ->group(bodies);
    cli::addNumbers(*mCommand, "--silo-orifices", o.siloOrifices,
                    "the silo's orifice diameters, mm (default 5 6 7 8; in --quick 4 5): "
                    "to run some of them, each from the same settled fill")
        ->type_name("D")
        ->group(bodies);
    cli::addNumber(*mCommand, "--silo-radius", o.siloRadius,
                   "the silo's radius, mm (0: 10; 4 in --quick); the grains follow the fill's "
                   "volume (4300 at 10 and 12 mm)")
        ->type_name("R")
        ->group(bodies);
    cli::addNumber(*mCommand, "--silo-height", o.siloHeight,
                   "the silo's fill height, mm (0: 12; 8 in --quick)")
        ->type_name("H")
        ->group(bodies);
    mCommand->add_flag("--quick", o.quick, "the fast version run by ctest: fewer points");
    mCommand->add_flag("--estimate", o.estimateOnly, "print what the run will take, and stop");
    cli::addThreads(*mCommand, mThreads, "worker threads (0: all cores)");
    addOutputOptions(*mCommand, o.outDir, o.plots, o.quiet, "print only the failures and the tally");
    mCommand->footer("Exit codes as every study's, and 5: a check failed (the table says which).");
}

bool VerifyCommand::chosen() const
{
    return mCommand->parsed();
}

int VerifyCommand::run(RunDistributor& ranks) const
{
    const verify::VerifyOptions& o = mOptions;
    verify::checkVerifyOptions(o);
    cli::checkThreads(mThreads);
    if (!ranks.isRoot()) return 0;  // the cases are short: rank 0 runs them all
    const ThreadLimit threads(mThreads, ranks);
    cli::checkOutputFolder(o.outDir);
    if (!o.quiet || o.estimateOnly)
        std::printf("verify plan: %s\n", verify::estimateVerification(o).text().c_str());
    if (o.estimateOnly) return 0;
    const Stopwatch wall;
    const verify::Report report = verify::runVerification(o, [&](const std::string& line) {
        if (!o.quiet) std::printf("%s\n", line.c_str()), std::fflush(stdout);
    });
    cli::prepareOutputFolder(o.outDir, kOwnFiles, o.quiet);
    const std::string checks = o.outDir + "/verify_checks.csv";
    verify::writeChecksCsv(report, checks);
    for (const verify::Series& s : report.series)
        verify::writeSeriesCsv(s, o.outDir + "/verify_" + s.name + ".csv");
    for (const verify::FrameSeries& f : report.frames) writeFrames(f, o.outDir);

    std::printf("%-26s %-12s %-24s %13s %13s %9s %8s %s\n", "case", "law", "quantity", "reference",
                "lsdem", "error", "tol", "");
    for (const verify::Check& c : report.checks) {
        if (o.quiet && c.passes()) continue;
        std::printf("%-26s %-12s %-24s %13.6g %13.6g %+8.3f%% %7.2f%% %s\n", c.caseName.c_str(),
                    c.formulation.c_str(), c.quantity.c_str(), c.reference, c.value,
                    100.0 * c.error(), 100.0 * c.tolerance,
                    c.informative ? "info" : c.passes() ? "pass" : "FAIL");
    }
    std::printf("%zu checks, %d failed, in %.1f s; wrote %s\n", report.checks.size(),
                report.failures(), wall.seconds(), checks.c_str());
    const int plots = o.plots ? cli::drawPlots("verify.py", {o.outDir}) : 0;
    if (!report.allPass()) return 5;
    return plots;
}

} // namespace lsdem
