/// lsdem-study: the paper's studies as one command each; writes CSV and PNG plots.

#include "common/CommandLine.h"
#include "common/StudyOutput.h"
#include "studies/Cube27Study.h"
#include "studies/SlabCommand.h"
#include "studies/TwoSpheresStudy.h"

#include "lsdem/ls/Error.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

namespace {

const char* const kUsage = R"(usage: lsdem-study two-spheres [options]

Two equal spheres pressed together along their centre line (Feldfogel et al. 2024, Fig. 1, 3):
grain 0 fixed, grain 1 displaced by δ from 0 to --delta-max; the force P on the centre line,
mean of random orientations, for each formulation, node count and stiffness.

  --formulation F...   original, adapted, single-node, volume (default: original adapted)
  --nodes N...         node counts (default: 500 1000 2000 4000 8000 16000)
  --kn K...            stiffnesses for every formulation (default: the paper's, kn = 1e9 N/mm
                       for original/single-node, kn* = 1e3 N/mm^3 for adapted/volume, and the
                       series 0.25, 0.5, 0.75, 1 x that at the node count nearest --k-nodes)
  --k-factors F...     the stiffness series factors (default 0.25 0.5 0.75 1)
  --k-nodes N          node count of the stiffness series (default 8000)
  --voxel VDP          level-set voxel size, mm (default 0.05)
  --radius R           sphere radius, mm (default 5)
  --delta-max D        largest overlap, mm (default 0.1)
  --steps S            overlap steps (default 10)
  --orientations M     random orientations averaged (default 3)
  --seed S             seed of the orientations (default 1)
  --testing T          symmetric (default) or one-way
  --out DIR            output folder (default results/two-spheres)
  --no-plots           write the CSV only
  -q, --quiet          print only the summary

Units: mm, N (forces), N/mm or N/mm^3 (stiffnesses). Writes DIR/two_spheres.csv and, with
python3-matplotlib, DIR/*.png.
)";

/// Read the option @a a if it is one of those the sphere studies share; false otherwise.
bool readSphereSeriesOption(lsdem::cli::Arguments& args, const std::string& a,
                            lsdem::SphereSeriesOptions& o)
{
    using namespace lsdem;
    if (a == "--formulation") {
        o.formulations.clear();
        for (const std::string& v : args.values(a)) o.formulations.push_back(parseFormulation(v));
    } else if (a == "--nodes") {
        o.nodeCounts = args.positiveCounts(a);
    } else if (a == "--kn") {
        o.stiffness = args.numbers(a);
    } else if (a == "--k-factors") {
        o.stiffnessFactors = args.numbers(a);
    } else if (a == "--k-nodes") {
        o.kSeriesNodes = int(std::clamp<long long>(args.integer(a), -1, 1000000000));
    } else if (a == "--voxel") {
        o.voxel = args.number(a);
    } else if (a == "--radius") {
        o.radius = args.number(a);
    } else if (a == "--delta-max") {
        o.deltaMax = args.number(a);
    } else if (a == "--orientations") {
        o.orientations = int(std::clamp<long long>(args.integer(a), -1, 1000000));
    } else if (a == "--seed") {
        o.seed = unsigned(args.integer(a));
    } else if (a == "--testing") {
        o.testing = parseNodeTesting(args.value(a));
    } else if (a == "--out") {
        o.outDir = args.value(a);
    } else if (a == "--no-plots") {
        o.plots = false;
    } else if (a == "-q" || a == "--quiet") {
        o.quiet = true;
    } else {
        return false;
    }
    return true;
}

int twoSpheres(lsdem::cli::Arguments& args)
{
    using namespace lsdem;
    TwoSpheresOptions o;
    while (!args.done()) {
        const std::string a = args.next();
        if (a == "-h" || a == "--help") {
            std::cout << kUsage;
            return 0;
        } else if (readSphereSeriesOption(args, a, o)) {
        } else if (a == "--steps") {
            o.steps = int(std::clamp<long long>(args.integer(a), -1, 1000000000));
        } else {
            throw Error("", "unknown option '" + a + "'", "see lsdem-study two-spheres --help");
        }
    }
    checkTwoSpheresOptions(o);
    cli::prepareOutputFolder(o.outDir);

    const auto start = std::chrono::steady_clock::now();
    const TwoSpheresResult result = runTwoSpheres(o);
    const std::string csv = o.outDir + "/two_spheres.csv";
    writeTwoSpheresCsv(result, o, csv);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // Summary: P at δ_max per formulation and N at the base stiffness, against the exact value.
    std::printf("two-spheres: R = %g mm, voxel = %g mm, δ_max = %g mm, %d orientations, %s testing\n",
                o.radius, o.voxel, o.deltaMax, o.orientations, nodeTestingName(o.testing).c_str());
    std::printf("%-12s %8s %10s %14s %12s %14s\n", "formulation", "N", "k", "P(δmax) [N]",
                "spread [N]", "vs exact adapted");
    for (const TwoSpheresRow& r : result.rows) {
        if (std::abs(r.delta - o.deltaMax) > 1e-12 * o.deltaMax) continue;
        const bool base = !o.stiffness.empty() || r.stiffness == defaultStiffness(r.formulation);
        if (!base) continue;
        std::printf("%-12s %8.0f %10.3g %14.6g %12.3g", formulationName(r.formulation).c_str(),
                    r.nodesActual, r.stiffness, r.forceMean, r.forceMax - r.forceMin);
        if (r.formulation == Formulation::Adapted)
            std::printf(" %+13.3f %%", 100.0 * (r.forceMean / r.forceExact - 1.0));
        std::printf("\n");
    }
    const NodeCheckStats& s = result.stats;
    const double contact = std::max(result.contactSeconds, 1e-9);
    std::printf("time %.2f s (bake %.2f s, contact %.3f s)\n", seconds, result.bakeSeconds,
                result.contactSeconds);
    std::printf("node checks: %lld considered (%.3g /s), %lld culled by bounds, %lld sampled "
                "(%.3g /s), %lld in contact\n",
                s.nodesConsidered, s.nodesConsidered / contact, s.nodesCulled, s.nodesSampled,
                s.nodesSampled / contact, s.nodesInContact);
    std::printf("wrote %s\n", csv.c_str());
    return o.plots ? cli::drawPlots(LSDEM_PLOT_DIR "/two_spheres.py", {csv, o.outDir}) : 0;
}

const char* const kCube27Usage = R"(usage: lsdem-study cube27 [options]

27 equal spheres in a 3x3x3 simple-cubic stack filling the box [0, 6R]^3 (Feldfogel et al.
2024, Fig. 4): fixed floor and side walls, a top wall moving down at constant speed by
--delta-max. The top wall's reaction P against its travel, for each formulation, node count
and stiffness; against the continuum closed form 9 pi k R delta^2 / (2 + 2 sqrt 2)^2.

  --formulation F...   original, adapted, single-node, volume (default: original adapted)
  --nodes N...         node counts (default: 500 1000 2000 4000 8000)
  --kn K...            stiffnesses for every formulation (default: the paper's, kn = 1e9 N/mm
                       for original/single-node, kn* = 1e3 N/mm^3 for adapted/volume, and the
                       series 0.25, 0.5, 0.75, 1 x that at the node count nearest --k-nodes)
  --k-factors F...     the stiffness series factors (default 0.25 0.5 0.75 1)
  --k-nodes N          node count of the stiffness series (default 4000, the paper's)
  --voxel VDP          level-set voxel size, mm (default 0.1)
  --radius R           sphere radius, mm (default 5)
  --delta-max D        top wall travel, mm (default 0.3)
  --speed V            top wall speed, mm/s, for every run (default: each run's loading lasts
                       --periods periods of a column's slowest mode, so v grows with sqrt(k))
  --periods Q          loading time in periods of a column's slowest mode (default 100)
  --steps S            loading steps (default: from --safety)
  --safety S           time step as a fraction of the stiffest grain's limit (default 0.2)
  --points P           delta values recorded per run (default 30)
  --orientations M     random orientation sets averaged (default 1)
  --seed S             seed of the orientations (default 1)
  --friction MU        Coulomb coefficient (default 0.3; shear stiffness ks = 0.5 kn)
  --restitution E      contact damping as a restitution coefficient (default 0.5)
  --damping L          global damping (default 0.3)
  --testing T          symmetric (default) or one-way
  --full               the paper-like study: nodes 500 ... 16000, 3 orientations, voxel 0.05
  --out DIR            output folder (default results/cube27)
  --no-plots           write the CSV only
  -q, --quiet          print only the summary

Prints the plan (each run's cost: 27 grains x nodes x steps) before starting. Units: mm, N,
s, tonne. Writes DIR/cube27.csv and, with python3-matplotlib, DIR/cube27_*.png.
)";

int cube27(lsdem::cli::Arguments& args)
{
    using namespace lsdem;
    Cube27Options o;
    {
        cli::Arguments scan = args;  // --full sets the defaults that later options refine
        while (!scan.done())
            if (scan.next() == "--full") o = cube27FullOptions();
    }
    while (!args.done()) {
        const std::string a = args.next();
        if (a == "-h" || a == "--help") {
            std::cout << kCube27Usage;
            return 0;
        } else if (readSphereSeriesOption(args, a, o)) {
        } else if (a == "--speed") {
            o.speed = args.number(a);
            if (!(o.speed > 0)) throw Error("", "--speed must be positive, got " + std::to_string(o.speed));
        } else if (a == "--periods") {
            o.periods = args.number(a);
        } else if (a == "--steps") {
            o.steps = args.integer(a);
            if (o.steps <= 0) throw Error("", "--steps must be positive");
        } else if (a == "--safety") {
            o.safety = args.number(a);
        } else if (a == "--points") {
            o.points = int(args.integer(a));
        } else if (a == "--friction") {
            o.friction = args.number(a);
        } else if (a == "--restitution") {
            o.restitution = args.number(a);
        } else if (a == "--damping") {
            o.globalDamping = args.number(a);
        } else if (a == "--full") {
            // applied before the loop
        } else {
            throw Error("", "unknown option '" + a + "'", "see lsdem-study cube27 --help");
        }
    }
    checkCube27Options(o);
    planCube27(o);  // refuses a --steps too few for any run, before anything is written
    cli::prepareOutputFolder(o.outDir);

    const auto start = std::chrono::steady_clock::now();
    const Cube27Result result = runCube27(o);
    const std::string csv = o.outDir + "/cube27.csv";
    writeCube27Csv(result, o, csv);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::printf("cube27: R = %g mm, voxel = %g mm, δ_max = %g mm, %d orientation(s), %s testing\n",
                o.radius, o.voxel, o.deltaMax, o.orientations, nodeTestingName(o.testing).c_str());
    std::printf("%-12s %8s %10s %14s %12s %14s %12s\n", "formulation", "N", "k", "P(δmax) [N]",
                "spread [N]", "P_exact [N]", "P/P_exact-1");
    double deltaEnd = 0.0;
    for (const Cube27Row& r : result.rows) deltaEnd = std::max(deltaEnd, r.delta);
    for (const Cube27Row& r : result.rows) {
        if (r.delta < deltaEnd * (1 - 1e-9)) continue;
        std::printf("%-12s %8.0f %10.3g %14.6g %12.3g %14.6g %+11.2f%%\n",
                    formulationName(r.formulation).c_str(), r.nodesActual, r.stiffness,
                    r.forceMean, r.forceMax - r.forceMin, r.forceExact,
                    100.0 * (r.forceMean / r.forceExact - 1.0));
    }
    std::printf("(original: P_exact uses kn* = kn·N/(4πR²), the continuum value of N uniformly "
                "spread nodes)\n");
    std::printf("time %.1f s (bake %.1f s, simulation %.1f s in %zu runs)\n", seconds,
                result.bakeSeconds, result.simulateSeconds, result.runs.size());
    std::printf("wrote %s\n", csv.c_str());
    return o.plots ? cli::drawPlots(LSDEM_PLOT_DIR "/cube27.py", {csv, o.outDir}) : 0;
}

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    return cli::runTool("lsdem-study", [&]() -> int {
        cli::Arguments args(argc, argv);
        if (args.done()) {
            std::cerr << kUsage;
            return 2;
        }
        const std::string study = args.next();
        if (study == "-h" || study == "--help") {
            std::cout << kUsage << "\n" << kCube27Usage << "\n" << slabUsage();
            return 0;
        }
        if (study == "two-spheres") return twoSpheres(args);
        if (study == "cube27") return cube27(args);
        if (study == "slab") return runSlabCommand(args, LSDEM_PLOT_DIR);
        throw Error("", "unknown study '" + study + "'", "available: two-spheres, cube27, slab");
    });
}
