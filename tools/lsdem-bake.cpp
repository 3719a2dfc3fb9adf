/// lsdem-bake: turn a closed mesh (OBJ, STL, PLY, ...) or an analytic shape into a grain asset
/// (.vdb): signed-distance level set, surface nodes with tributary areas, mass properties.

#include "common/CommandLine.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/Error.h"
#include "lsdem/ls/Stopwatch.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <optional>

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
    std::string outputPath;
    bool quiet = false;
    // The options whose presence matters (which shape, which node placement).
    CLI::Option *sphereOption = nullptr, *boxOption = nullptr, *ellipsoidOption = nullptr;
    CLI::Option *spacingOption = nullptr, *countOption = nullptr, *meshNodesOption = nullptr;
};

/// Every option of lsdem-bake, its default and its help.
void addOptions(CLI::App& app, BakeCommandLine& c)
{
    using lsdem::cli::addInteger;
    using lsdem::cli::addNumber;
    using lsdem::cli::addNumbers;
    const std::string input = "Input (one of)";
    app.add_option("mesh", c.meshPaths,
                   "closed triangle mesh file (OBJ, STL, PLY, or any format assimp reads)")
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
    addNumber(app, "--voxel", c.options.voxelSize,
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
                                "by isotropic remeshing to edge length SDP")
                          ->type_name("SDP")
                          ->default_str("")
                          ->group(nodes);
    c.countOption = addInteger(app, "--nodes", c.nodeCount, "by remeshing to about N nodes")
                        ->type_name("N")
                        ->default_str("")
                        ->group(nodes);
    c.meshNodesOption = app.add_flag("--mesh-nodes", "at the input mesh's own vertices")
                            ->group(nodes);
    app.add_option("--areas", c.areas,
                   "tributary areas: 'mesh' (1/3 of each incident triangle) or\n"
                   "'uniform' (total area / N, as in Feldfogel et al. 2024)")
        ->type_name("RULE")
        ->capture_default_str()
        ->group(nodes);

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
    if (c.meshPaths.size() > 1)
        throw Error("", "more than one input mesh ('" + c.meshPaths[0] + "', '" +
                            c.meshPaths[1] + "')");
    const size_t placements = c.spacingOption->count() + c.countOption->count() +
                              c.meshNodesOption->count();
    if (placements > 1) throw Error("", "give only one of --node-spacing, --nodes, --mesh-nodes");
    if (c.spacingOption->count()) o.nodePlacement = lsdem::NodePlacement::Spacing;
    if (c.meshNodesOption->count()) o.nodePlacement = lsdem::NodePlacement::MeshVertices;
    if (c.countOption->count()) {
        o.nodePlacement = lsdem::NodePlacement::Count;
        if (c.nodeCount < 4 || c.nodeCount > 100000000)
            throw Error("", "--nodes wants a count from 4 to 1e8, got " +
                                std::to_string(c.nodeCount));
        o.nodeCount = int(c.nodeCount);
    }
    if (c.areas == "mesh") o.areaRule = lsdem::AreaRule::Mesh;
    else if (c.areas == "uniform") o.areaRule = lsdem::AreaRule::Uniform;
    else throw Error("", "--areas wants 'mesh' or 'uniform', got '" + c.areas + "'");
    if (!(c.memoryBudgetGb > 0)) throw Error("", "--memory-budget-gb must be positive");
    o.memoryBudgetBytes = c.memoryBudgetGb * kGiB;

    if (c.meshPaths.empty() && !shape)
        throw Error("", "no input: give a mesh file or --sphere/--box/--ellipsoid",
                    "see lsdem-bake --help");
    if (!c.meshPaths.empty() && shape)
        throw Error("", "give either a mesh file or an analytic shape, not both");
    if (placements == 0)
        throw Error("", "say how to place surface nodes",
                    "add --node-spacing SDP, --nodes N or --mesh-nodes");
    if (o.voxelSize == 0.0) throw Error("", "the voxel size is missing", "add --voxel VDP");
    if (c.outputPath.empty()) throw Error("", "no output file", "add -o OUT.vdb");
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
        "             (--node-spacing SDP | --nodes N | --mesh-nodes) -o OUT.vdb",
        "lsdem-bake");
    cli::applyConventions(app);
    app.footer("All lengths are in the mesh's own unit (e.g. mm); lsdem never converts units.\n"
               "Exit codes: 0 baked, 1 bad input, 2 no arguments (this help on stderr), "
               "3 internal error.");
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
