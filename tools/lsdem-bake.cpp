/// lsdem-bake: turn a closed mesh (OBJ, STL, PLY, ...) or an analytic shape into a grain asset
/// (.vdb): signed-distance level set, surface nodes with tributary areas, mass properties.

#include "common/CommandLine.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/BatchBake.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <optional>

#include <unistd.h>

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

std::string quoteArgs(int argc, char** argv)
{
    std::string text;
    for (int i = 1; i < argc; ++i) text += (i > 1 ? " " : "") + std::string(argv[i]);
    return text;
}

/// What the command line says, before it is checked and turned into BakeOptions.
struct BakeCommandLine
{
    std::vector<std::string> meshPaths;
    double sphereRadius = 0.0;
    std::vector<double> box, ellipsoid;
    lsdem::BakeOptions options;
    double memoryBudgetGb = options.memoryBudgetBytes / kGiB;
    long long nodeCount = 0;
    std::string areas = "mesh";
    std::string nodeLayout = "auto";
    CLI::Option* nodeLayoutOption = nullptr;
    std::string outputPath;
    bool quiet = false;
    // Batch mode (--out-dir): many files, sizes relative to each grain.
    std::string outDir;
    double voxelPerSize = 0.0, nodeSpacingPerSize = 0.0;
    long long threads = 0;
    bool rebake = false;
    CLI::Option *threadsOption = nullptr, *rebakeOption = nullptr;
    // The options whose presence matters (which shape, which node placement).
    CLI::Option *sphereOption = nullptr, *boxOption = nullptr, *ellipsoidOption = nullptr;
    CLI::Option *spacingOption = nullptr, *countOption = nullptr, *meshNodesOption = nullptr;
    CLI::Option *voxelOption = nullptr, *voxelPerSizeOption = nullptr,
                *spacingPerSizeOption = nullptr;
};

/// Every option of lsdem-bake, its default and its help.
// Long by nature: one entry per option, in the order --help lists them.
void addOptions(CLI::App& app, BakeCommandLine& c)
{
    using lsdem::cli::addInteger;
    using lsdem::cli::addNumber;
    using lsdem::cli::addNumbers;
    const std::string input = "Input (one of)";
    app.add_option("mesh", c.meshPaths,
                   "closed triangle mesh file (OBJ, STL, PLY, or any format assimp\n"
                   "reads); several with --out-dir")
        ->type_name("MESH")
        ->group(input);
    c.sphereOption = addNumber(app, "--sphere", c.sphereRadius, "analytic sphere of radius R")
                         ->type_name("R")
                         ->default_str("")
                         ->group(input);
    c.boxOption = addNumbers(app, "--box", c.box, "analytic box with full edge lengths A, B, C", 3)
                      ->option_text("A B C")
                      ->group(input);
    c.ellipsoidOption =
        addNumbers(app, "--ellipsoid", c.ellipsoid, "analytic ellipsoid with semi-axes A, B, C", 3)
            ->option_text("A B C")
            ->group(input);

    const std::string levelSet = "Level set";
    c.voxelOption = addNumber(app, "--voxel", c.options.voxelSize,
                              "level-set voxel size (volume discretization parameter)")
                        ->type_name("VDP")
                        ->default_str("")
                        ->group(levelSet);
    addInteger(app, "--band", c.options.exteriorBandVoxels, "exterior narrow-band width, voxels")
        ->type_name("VOXELS")
        ->group(levelSet);
    addNumber(app, "--memory-budget-gb", c.memoryBudgetGb,
              "refuse level sets estimated above G GiB")
        ->type_name("G")
        ->group(levelSet);

    const std::string nodes = "Surface nodes (one of)";
    c.spacingOption = addNumber(app, "--node-spacing", c.options.nodeSpacing,
                                "about SDP apart (the edges of equilateral\n"
                                "triangles holding as many nodes)")
                          ->type_name("SDP")
                          ->default_str("")
                          ->group(nodes);
    c.countOption = addInteger(app, "--nodes", c.nodeCount, "about N nodes (exactly N on a mesh\n"
                                                            "laid out centroidally)")
                        ->type_name("N")
                        ->default_str("")
                        ->group(nodes);
    c.meshNodesOption = app.add_flag("--mesh-nodes", "at the input mesh's own vertices")
                            ->group(nodes);
    c.nodeLayoutOption = app.add_option("--node-layout", c.nodeLayout,
                   "how a mesh's nodes are placed: 'centroidal' (each node at the\n"
                   "centroid of its Voronoi cell on the mesh; fast on fine scans),\n"
                   "'remesh' (the vertices of the mesh remeshed, sharp edges kept),\n"
                   "or 'auto': centroidal unless the mesh has sharp edges (over 30°)\n"
                   "in lines, as a block's (a scan's noise, scattered, is not)")
        ->type_name("LAYOUT")
        ->capture_default_str()
        ->group(nodes);
    app.add_option("--areas", c.areas,
                   "tributary areas: 'mesh' (each node's own share of the surface:\n"
                   "its cell, or 1/3 of each incident triangle of a remeshed one) or\n"
                   "'uniform' (total area / N, as in Feldfogel et al. 2024)")
        ->type_name("RULE")
        ->capture_default_str()
        ->group(nodes);

    const std::string batch = "Batch (several files, one asset each, and catalog.csv)";
    app.add_option("--out-dir", c.outDir,
                   "bake every MESH into DIR/NAME.vdb (NAME: the file's stem) and\n"
                   "write DIR/catalog.csv; unchanged files are not baked again")
        ->type_name("DIR")
        ->group(batch);
    c.voxelPerSizeOption =
        addNumber(app, "--voxel-per-size", c.voxelPerSize,
                  "voxel = F x each grain's equivalent diameter (instead of --voxel)")
            ->type_name("F")
            ->default_str("")
            ->group(batch);
    c.spacingPerSizeOption =
        addNumber(app, "--node-spacing-per-size", c.nodeSpacingPerSize,
                  "node spacing = F x each grain's equivalent diameter")
            ->type_name("F")
            ->default_str("")
            ->group(batch);
    c.threadsOption =
        lsdem::cli::addThreads(app, c.threads, "files baked at once (default: all cores)")
            ->group(batch);
    c.rebakeOption =
        app.add_flag("--rebake", c.rebake,
                     "bake every file, even those unchanged since the catalogue")
            ->group(batch);

    const std::string output = "Output";
    app.add_option("-o,--output", c.outputPath, "the asset to write (written atomically)")
        ->type_name("FILE")
        ->group(output);
    app.add_flag("-q,--quiet", c.quiet, "print nothing but warnings and errors")->group(output);
}

/// The analytic shape the command line names, if any; Error if it names more than one.
std::optional<lsdem::AnalyticShape> chosenShape(const BakeCommandLine& c)
{
    using lsdem::AnalyticShape;
    // Uses, not options: a repeated --sphere is as ambiguous as --sphere with --box.
    const size_t given = c.sphereOption->count() + (c.boxOption->count() + 2) / 3 +
                         (c.ellipsoidOption->count() + 2) / 3;
    if (given > 1) throw lsdem::Error("", "give only one analytic shape");
    if (c.sphereOption->count()) return AnalyticShape::sphere(c.sphereRadius);
    if (c.boxOption->count()) return AnalyticShape::box(c.box[0], c.box[1], c.box[2]);
    if (c.ellipsoidOption->count())
        return AnalyticShape::ellipsoid(c.ellipsoid[0], c.ellipsoid[1], c.ellipsoid[2]);
    return std::nullopt;
}

/// Check what the options do not check one by one, and fill in c.options.
void checkAndResolve(BakeCommandLine& c, const std::optional<lsdem::AnalyticShape>& shape)
{
    using lsdem::Error;
    lsdem::BakeOptions& o = c.options;
    const bool batch = !c.outDir.empty();
    if (c.meshPaths.size() > 1 && !batch)
        throw Error("", "more than one input mesh ('" + c.meshPaths[0] + "', '" +
                            c.meshPaths[1] + "')",
                    "bake several files with --out-dir DIR");
    if (!batch && (c.voxelPerSizeOption->count() || c.spacingPerSizeOption->count()))
        throw Error("", "--voxel-per-size and --node-spacing-per-size need --out-dir",
                    "give --out-dir DIR, or --voxel and --node-spacing for one file");
    // Said rather than ignored: a user who gives them expects a batch.
    for (const CLI::Option* batchOnly : {c.threadsOption, c.rebakeOption})
        if (!batch && batchOnly->count())
            throw Error("", batchOnly->get_name() + " applies to --out-dir batches only",
                        "drop " + batchOnly->get_name() + " to bake one file, or give --out-dir DIR");
    const size_t placements = c.spacingOption->count() + c.countOption->count() +
                              c.meshNodesOption->count() + c.spacingPerSizeOption->count();
    if (placements > 1)
        throw Error("", "give only one of --node-spacing, --node-spacing-per-size, --nodes, "
                        "--mesh-nodes");
    if (c.spacingOption->count() || c.spacingPerSizeOption->count())
        o.nodePlacement = lsdem::NodePlacement::Spacing;
    if (c.meshNodesOption->count()) o.nodePlacement = lsdem::NodePlacement::MeshVertices;
    if (c.countOption->count()) {
        o.nodePlacement = lsdem::NodePlacement::Count;
        if (c.nodeCount < 4 || c.nodeCount > lsdem::kMaxNodeCount)
            throw Error("", "--nodes wants a count from 4 to 1e8, got " +
                                std::to_string(c.nodeCount));
        o.nodeCount = int(c.nodeCount);
    }
    o.nodeLayout = lsdem::nodeLayoutNamed(c.nodeLayout);
    // Said rather than ignored, as a scene says it.
    if (c.nodeLayoutOption->count() && shape)
        throw Error("", "--node-layout applies to meshes: an analytic shape's nodes are "
                        "remeshed onto its exact surface", "drop --node-layout");
    if (c.nodeLayoutOption->count() && c.meshNodesOption->count())
        throw Error("", "--node-layout has no effect with --mesh-nodes",
                    "drop --node-layout, or give --node-spacing or --nodes");
    if (c.areas == "mesh") o.areaRule = lsdem::AreaRule::Mesh;
    else if (c.areas == "uniform") o.areaRule = lsdem::AreaRule::Uniform;
    else throw Error("", "--areas wants 'mesh' or 'uniform', got '" + c.areas + "'");
    if (!(c.memoryBudgetGb > 0)) throw Error("", "--memory-budget-gb must be positive");
    o.memoryBudgetBytes = c.memoryBudgetGb * kGiB;

    if (c.meshPaths.empty() && !shape)
        throw Error("", "no input: give a mesh file or --sphere/--box/--ellipsoid",
                    "see lsdem-bake --help");
    if (batch) {
        if (shape) throw Error("", "--out-dir bakes mesh files, not analytic shapes",
                               "bake a shape alone with -o OUT.vdb");
        if (!c.outputPath.empty())
            throw Error("", "give either -o (one file) or --out-dir (a batch), not both");
        if (c.voxelOption->count() + c.voxelPerSizeOption->count() != 1)
            throw Error("", "give exactly one of --voxel and --voxel-per-size",
                        "e.g. --voxel-per-size 0.03");
        if (c.voxelPerSizeOption->count() && !(c.voxelPerSize > 0.0 && c.voxelPerSize < 1.0))
            throw Error("", "--voxel-per-size wants a fraction in (0, 1), e.g. 0.03");
        if (c.spacingPerSizeOption->count() &&
            !(c.nodeSpacingPerSize > 0.0 && c.nodeSpacingPerSize < 1.0))
            throw Error("", "--node-spacing-per-size wants a fraction in (0, 1), e.g. 0.05");
        if (placements == 0)
            throw Error("", "say how to place surface nodes",
                        "add --node-spacing SDP, --node-spacing-per-size F, --nodes N or "
                        "--mesh-nodes");
        return;
    }
    if (!c.meshPaths.empty() && shape)
        throw Error("", "give either a mesh file or an analytic shape, not both");
    if (placements == 0)
        throw Error("", "say how to place surface nodes",
                    "add --node-spacing SDP, --nodes N or --mesh-nodes");
    if (o.voxelSize == 0.0) throw Error("", "the voxel size is missing", "add --voxel VDP");
    if (c.outputPath.empty()) throw Error("", "no output file", "add -o OUT.vdb");
    lsdem::cli::refuseOutputOverInput(c.outputPath, "-o", c.meshPaths);
    lsdem::checkOutputFile(c.outputPath);  // now, not after a bake of minutes
}

/// "1 h 02 min", "3 min 20 s", "12 s".
std::string showDuration(double seconds)
{
    const long long s = static_cast<long long>(seconds + 0.5);
    char text[64];
    if (s >= 3600) std::snprintf(text, sizeof text, "%lld h %02lld min", s / 3600, s / 60 % 60);
    else if (s >= 60) std::snprintf(text, sizeof text, "%lld min %02lld s", s / 60, s % 60);
    else std::snprintf(text, sizeof text, "%lld s", s);
    return text;
}

/// The progress line on stderr: redrawn in place on a terminal, else a line every few seconds.
class ProgressLine
{
public:
    explicit ProgressLine(bool enabled) : mEnabled(enabled), mTerminal(::isatty(2) != 0) {}

    void update(size_t done, size_t total, const std::string& file)
    {
        if (!mEnabled) return;
        const double elapsed = mClock.seconds();
        if (!mTerminal && done < total && elapsed - mLastPrint < 5.0) return;
        mLastPrint = elapsed;
        const double rate = done / std::max(elapsed, 1e-9);
        const double eta = (total - done) / std::max(rate, 1e-9);
        std::fprintf(stderr, "%s[%zu/%zu] %3.0f %%  %.2f files/s  ETA %s  %s%s",
                     mTerminal ? "\r\033[K" : "", done, total, 100.0 * done / total, rate,
                     showDuration(eta).c_str(), file.c_str(), mTerminal ? "" : "\n");
        if (mTerminal && done == total) std::fputc('\n', stderr);
        std::fflush(stderr);
    }

private:
    bool mEnabled, mTerminal;
    lsdem::Stopwatch mClock;
    double mLastPrint = -1e9;
};

/// lsdem-bake --out-dir: every file, the catalogue, a summary; exit 4 if some file failed.
int runBatch(const BakeCommandLine& c)
{
    using namespace lsdem;
    BatchBakeOptions batch;
    batch.bake = c.options;
    batch.voxelPerSize = c.voxelPerSize;
    batch.nodeSpacingPerSize = c.nodeSpacingPerSize;
    batch.outDir = c.outDir;
    batch.threads = static_cast<int>(c.threads);  // at most kMaxThreads
    batch.rebake = c.rebake;
    const Stopwatch clock;
    ProgressLine progress(!c.quiet);
    const BatchBakeReport report =
        bakeBatch(c.meshPaths, batch, [&](size_t done, size_t total, const std::string& file) {
            progress.update(done, total, file);
        });
    const double seconds = clock.seconds();
    for (const auto& w : report.warnings) std::cerr << "lsdem-bake: warning: " << w << "\n";
    if (!c.quiet)
        std::printf("baked %d, unchanged %d, failed %zu of %zu files in %.2f s (%.3g baked/s); "
                    "catalogue %s (%zu assets)\n",
                    report.baked, report.unchanged, report.failures.size(), c.meshPaths.size(),
                    seconds, report.baked / std::max(seconds, 1e-9), report.catalogPath.c_str(),
                    report.entries.size());
    if (report.failures.empty()) return 0;
    std::fprintf(stderr, "lsdem-bake: %zu of %zu files failed and were skipped:\n",
                 report.failures.size(), c.meshPaths.size());
    for (const BatchFailure& f : report.failures) {
        std::string text = f.message;  // its fix line indented under it
        for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1))
            text.insert(at + 1, "    ");
        std::fprintf(stderr, "  %s\n", text.c_str());
    }
    return 4;
}

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    CLI::App app(
        "Bakes a grain asset: one .vdb file with the signed distance (voxel size VDP, interior\n"
        "filled), the surface nodes with their tributary areas and outward normals, and the\n"
        "unit-density mass properties, all in the grain's principal frame (centroid at the "
        "origin).\n\n"
        "  lsdem-bake (MESH | --sphere R | --box A B C | --ellipsoid A B C) --voxel VDP\n"
        "             (--node-spacing SDP | --nodes N | --mesh-nodes) -o OUT.vdb\n"
        "  lsdem-bake MESH... --out-dir DIR (--voxel VDP | --voxel-per-size F)\n"
        "             (--node-spacing SDP | --node-spacing-per-size F | --nodes N) [--threads N]",
        "lsdem-bake");
    cli::applyConventions(app);
    app.footer("All lengths are in the mesh's own unit (e.g. mm); lsdem never converts units.\n"
               "Exit codes: 0 baked, 1 bad input, 2 no arguments (this help on stderr), "
               "3 internal error,\n4 some files of a batch failed (the others are baked and in "
               "the catalogue).");
    BakeCommandLine c;
    addOptions(app, c);
    if (argc < 2) {
        std::cerr << app.help();
        return 2;
    }
    return cli::runTool("lsdem-bake", [&]() -> int {
        if (const auto exitCode = cli::parse(app, argc, argv)) return *exitCode;
        const std::optional<AnalyticShape> shape = chosenShape(c);
        checkAndResolve(c, shape);
        if (!c.outDir.empty()) return runBatch(c);
        const BakeOptions& options = c.options;
        const std::string& outputPath = c.outputPath;
        c.options.optionsText = quoteArgs(argc, argv);

        const Stopwatch bakeTime;
        std::vector<std::string> warnings;
        const GrainAsset asset = shape ? bakeAnalytic(*shape, options, warnings)
                                       : bakeMeshFile(c.meshPaths[0], options, warnings);
        for (const auto& w : warnings) std::cerr << "lsdem-bake: warning: " << w << "\n";
        saveAsset(asset, outputPath);
        const double seconds = bakeTime.seconds();
        if (!c.quiet) {
            std::printf("baked %s -> %s in %.2f s\n", asset.provenance.source.c_str(),
                        outputPath.c_str(), seconds);
            std::printf("  voxel %.6g, %zu nodes (spacing mean %.4g, min %.4g, max %.4g), "
                        "node area %.6g\n",
                        asset.voxelSize, asset.nodes.size(), asset.spacing.mean,
                        asset.spacing.min, asset.spacing.max, asset.nodes.totalArea());
            std::printf("  volume %.6g, principal moments (unit density) %.6g %.6g %.6g\n",
                        asset.mass.volume, asset.mass.inertia(0, 0), asset.mass.inertia(1, 1),
                        asset.mass.inertia(2, 2));
        }
        return 0;
    });
}
