/// lsdem-bake: turn a closed mesh (OBJ, STL, PLY, ...) or an analytic shape into a grain asset
/// (.vdb): signed-distance level set, surface nodes with tributary areas, mass properties.

#include "common/CommandLine.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/ls/Error.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

namespace {

const char* const kUsage = R"(usage: lsdem-bake (MESH | --sphere R | --box A B C | --ellipsoid A B C)
                  --voxel VDP (--node-spacing SDP | --nodes N | --mesh-nodes)
                  [--areas mesh|uniform] [--band VOXELS] [--memory-budget-gb G]
                  -o OUT.vdb

Bakes a grain asset: one .vdb file with the signed distance (voxel size VDP, interior filled),
the surface nodes with their tributary areas and outward normals, and the unit-density mass
properties, all in the grain's principal frame (centroid at the origin).

  MESH                 closed triangle mesh file (OBJ, STL, PLY, or any format assimp reads)
  --sphere R           analytic sphere of radius R
  --box A B C          analytic box with full edge lengths A, B, C
  --ellipsoid A B C    analytic ellipsoid with semi-axes A, B, C
  --voxel VDP          level-set voxel size (volume discretization parameter)
  --node-spacing SDP   surface nodes by isotropic remeshing to edge length SDP
  --nodes N            surface nodes by remeshing to about N nodes
  --mesh-nodes         surface nodes at the input mesh's own vertices
  --areas RULE         tributary areas: 'mesh' (1/3 of each incident triangle; default) or
                       'uniform' (total area / N, as in Feldfogel et al. 2024)
  --band VOXELS        exterior narrow-band width in voxels (default 3)
  --memory-budget-gb G refuse level sets estimated above G GiB (default 4)
  -o, --output FILE    the asset to write (written atomically)
  -q, --quiet          print nothing but warnings and errors

All lengths are in the mesh's own unit (e.g. mm); lsdem never converts units.
)";

std::string quoteArgs(int argc, char** argv)
{
    std::string text;
    for (int i = 1; i < argc; ++i) text += (i > 1 ? " " : "") + std::string(argv[i]);
    return text;
}

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    return cli::runTool("lsdem-bake", [&]() -> int {
        cli::Arguments args(argc, argv);
        std::string meshPath, outputPath;
        std::optional<AnalyticShape> shape;
        BakeOptions options;
        bool placementGiven = false, quiet = false;
        auto setPlacement = [&](NodePlacement p) {
            if (placementGiven)
                throw Error("", "give only one of --node-spacing, --nodes, --mesh-nodes");
            placementGiven = true;
            options.nodePlacement = p;
        };
        auto setShape = [&](const AnalyticShape& s) {
            if (shape) throw Error("", "give only one analytic shape");
            shape = s;
        };
        if (args.done()) {
            std::cerr << kUsage;
            return 2;
        }
        while (!args.done()) {
            const std::string a = args.next();
            if (a == "-h" || a == "--help") {
                std::cout << kUsage;
                return 0;
            } else if (a == "--sphere") {
                setShape(AnalyticShape::sphere(args.number(a)));
            } else if (a == "--box" || a == "--ellipsoid") {
                const double x = args.number(a), y = args.number(a), z = args.number(a);
                setShape(a == "--box" ? AnalyticShape::box(x, y, z)
                                      : AnalyticShape::ellipsoid(x, y, z));
            } else if (a == "--voxel") {
                options.voxelSize = args.number(a);
            } else if (a == "--node-spacing") {
                setPlacement(NodePlacement::Spacing);
                options.nodeSpacing = args.number(a);
            } else if (a == "--nodes") {
                setPlacement(NodePlacement::Count);
                const long long n = args.integer(a);
                if (n < 4 || n > 100000000)
                    throw Error("", "--nodes wants a count from 4 to 1e8, got " +
                                        std::to_string(n));
                options.nodeCount = int(n);
            } else if (a == "--mesh-nodes") {
                setPlacement(NodePlacement::MeshVertices);
            } else if (a == "--areas") {
                const std::string rule = args.value(a);
                if (rule == "mesh") options.areaRule = AreaRule::Mesh;
                else if (rule == "uniform") options.areaRule = AreaRule::Uniform;
                else throw Error("", "--areas wants 'mesh' or 'uniform', got '" + rule + "'");
            } else if (a == "--band") {
                options.exteriorBandVoxels = int(args.integer(a));
            } else if (a == "--memory-budget-gb") {
                const double gb = args.number(a);
                if (!(gb > 0)) throw Error("", "--memory-budget-gb must be positive");
                options.memoryBudgetBytes = gb * 1024.0 * 1024.0 * 1024.0;
            } else if (a == "-o" || a == "--output") {
                outputPath = args.value(a);
            } else if (a == "-q" || a == "--quiet") {
                quiet = true;
            } else if (!a.empty() && a[0] == '-') {
                throw Error("", "unknown option '" + a + "'", "see lsdem-bake --help");
            } else {
                if (!meshPath.empty())
                    throw Error("", "more than one input mesh ('" + meshPath + "', '" + a + "')");
                meshPath = a;
            }
        }
        if (meshPath.empty() && !shape)
            throw Error("", "no input: give a mesh file or --sphere/--box/--ellipsoid",
                        "see lsdem-bake --help");
        if (!meshPath.empty() && shape)
            throw Error("", "give either a mesh file or an analytic shape, not both");
        if (!placementGiven)
            throw Error("", "say how to place surface nodes",
                        "add --node-spacing SDP, --nodes N or --mesh-nodes");
        if (options.voxelSize == 0.0)
            throw Error("", "the voxel size is missing", "add --voxel VDP");
        if (outputPath.empty()) throw Error("", "no output file", "add -o OUT.vdb");
        options.optionsText = quoteArgs(argc, argv);

        const auto start = std::chrono::steady_clock::now();
        std::vector<std::string> warnings;
        const GrainAsset asset = shape ? bakeAnalytic(*shape, options, warnings)
                                       : bakeMeshFile(meshPath, options, warnings);
        for (const auto& w : warnings) std::cerr << "lsdem-bake: warning: " << w << "\n";
        saveAsset(asset, outputPath);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!quiet) {
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
