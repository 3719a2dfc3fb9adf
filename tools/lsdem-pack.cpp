/// lsdem-pack: fill a box or a vertical cylinder with a mixture of grain assets (random
/// insertion, then deposition under gravity) and write the packing as a grains CSV that a scene
/// reads with [[grain_files]].

#include "common/CommandLine.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/RunInParallel.h"
#include "lsdem/scene/CatalogMixture.h"
#include "lsdem/scene/GrainsCsv.h"
#include "lsdem/scene/Packing.h"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace {

using lsdem::Error;

struct PackCommandLine
{
    std::vector<std::string> files, names;
    std::string catalog, set;
    std::vector<double> fractions, box, cylinder;
    long long count = 0, seed = 1, threads = 0;
    std::string out;
    lsdem::PackingOptions options;
};

/// The mixture: the asset files given, or every asset of the catalogue.
std::vector<lsdem::PackingComponent> readMixture(const PackCommandLine& c)
{
    if (!c.catalog.empty() && !c.files.empty())
        throw Error("", "both asset files and --catalog are given",
                    "give either ASSET.vdb files or --catalog assets/catalog.csv --set NAME");
    if (c.catalog.empty() && !c.set.empty())
        throw Error("", "--set names the asset set of a catalogue, and no --catalog is given",
                    "add --catalog assets/catalog.csv, or remove --set");
    if (c.catalog.empty() && c.files.empty())
        throw Error("", "no grain assets given",
                    "give one or more .vdb files, or --catalog assets/catalog.csv --set NAME");
    if (!c.catalog.empty() && c.set.empty())
        throw Error("", "--catalog needs --set NAME",
                    "give the NAME of the scene's [asset_sets.NAME] that reads the catalogue: "
                    "the CSV names its assets NAME/ASSET as that set does");
    if (!c.catalog.empty() && !c.names.empty())
        throw Error("", "--names is for asset files; a catalogue's assets are named SET/ASSET",
                    "remove --names (use --set to choose SET)");
    if (!c.names.empty() && c.names.size() != c.files.size())
        throw Error("", "--names has " + std::to_string(c.names.size()) + " names for " +
                            std::to_string(c.files.size()) + " assets",
                    "give one name per asset");
    std::vector<lsdem::PackingComponent> mixture;
    if (!c.catalog.empty()) {
        mixture = lsdem::catalogMixture(c.catalog, c.set);
    } else {
        mixture.resize(c.files.size());
        lsdem::runInParallel(c.files.size(), [&](size_t k) {
            lsdem::PackingComponent& p = mixture[k];
            p.name = c.names.empty() ? std::filesystem::path(c.files[k]).stem().string()
                                     : c.names[k];
            // For packing only: without normals, these copies cannot be saved.
            p.asset = lsdem::loadAsset(c.files[k], lsdem::NodeNormals::Skip);
        }).rethrowIfAny();
    }
    if (!c.fractions.empty() && c.fractions.size() != mixture.size())
        throw Error("", "--fractions has " + std::to_string(c.fractions.size()) + " values for " +
                            std::to_string(mixture.size()) +
                            (c.catalog.empty() ? " assets"
                                               : " assets of the catalogue " + c.catalog),
                    c.catalog.empty() ? "give one fraction per asset"
                                      : "give one fraction per catalogue row, in its order, or "
                                        "none for equal shares");
    for (size_t k = 0; k < c.fractions.size(); ++k) mixture[k].fraction = c.fractions[k];
    return mixture;
}

/// The container: exactly one of --box and --cylinder.
void readContainer(const PackCommandLine& c, lsdem::PackingOptions& o)
{
    if (c.box.empty() == c.cylinder.empty())
        throw Error("",
                    c.box.empty() ? "no container given" : "both --box and --cylinder are given",
                    "pass either --box X0 Y0 Z0 X1 Y1 Z1 or --cylinder CX CY RADIUS Z0 Z1");
    if (!c.box.empty()) {
        o.boxMin = lsdem::Vec3(c.box[0], c.box[1], c.box[2]);
        o.boxMax = lsdem::Vec3(c.box[3], c.box[4], c.box[5]);
        return;
    }
    lsdem::PackingCylinder cyl;
    cyl.x = c.cylinder[0];
    cyl.y = c.cylinder[1];
    cyl.radius = c.cylinder[2];
    cyl.zMin = c.cylinder[3];
    cyl.zMax = c.cylinder[4];
    if (!(cyl.radius > 0.0))
        throw Error("", "--cylinder: the radius must be > 0", "give --cylinder CX CY RADIUS Z0 Z1");
    if (!(cyl.zMax > cyl.zMin))
        throw Error("", "--cylinder: Z1 must exceed Z0 (the floor and the lid)",
                    "give --cylinder CX CY RADIUS Z0 Z1 with Z1 > Z0");
    o.cylinder = cyl;
}

/// The options after the assets, in the order --help lists them.
void addOptions(CLI::App& app, PackCommandLine& c)
{
    app.add_option("assets", c.files, "grain assets baked by lsdem-bake")->type_name("ASSET.vdb");
    app.add_option("--catalog", c.catalog,
                   "pack every asset of this catalogue (lsdem-bake --out-dir writes it)")
        ->type_name("CSV");
    app.add_option("--set", c.set,
                   "with --catalog: the scene's [asset_sets.NAME] that reads it; the CSV names "
                   "the assets NAME/ASSET")
        ->type_name("NAME");
    lsdem::cli::addNumbers(app, "--fractions", c.fractions,
                           "share of the grain count per asset or catalogue row (default: equal)");
    lsdem::cli::addTexts(app, "--names", c.names,
                   "asset names written in the CSV, as the scene's [assets.NAME]\n(default: "
                   "the file names without .vdb)")
        ->type_name("NAME");
    lsdem::cli::addInteger(app, "--count", c.count, "grains to pack")->default_str("")->required();
    lsdem::cli::addNumbers(app, "--box", c.box, "the inside of the box: min and max corners", 6);
    lsdem::cli::addNumbers(app, "--cylinder", c.cylinder,
                           "a vertical cylinder instead: axis at (CX, CY), RADIUS, floor Z0, "
                           "lid Z1", 5);
    lsdem::cli::addInteger(app, "--seed", c.seed, "random seed (positions, orientations, order)");
    lsdem::cli::addNumber(app, "--friction", c.options.friction,
                          "Coulomb friction during deposition (0: densest packing)");
    lsdem::cli::addNumber(app, "--settle", c.options.settleTolerance,
                          "at rest when kinetic energy < this x sum of m*g*d");
    app.add_option("-o,--out", c.out, "the grains CSV to write (atomically)")->type_name("FILE");
    lsdem::cli::addThreads(app, c.threads, "worker threads (default: all cores)");
}

/// The packing the parsed command line @a c asks for, written to its -o file; the exit code.
int pack(PackCommandLine& c)
{
    if (c.out.empty()) throw Error("", "no output file given", "pass -o packing.csv");
    std::vector<std::string> inputs = c.files;
    if (!c.catalog.empty()) {
        inputs.push_back(c.catalog);
        // The catalogue's assets are inputs too: -o cat/grain_0000.vdb replaced one.
        for (const std::string& asset : lsdem::catalogAssetFiles(c.catalog))
            inputs.push_back(asset);
    }
    lsdem::cli::refuseOutputOverInput(c.out, "-o", inputs);
    lsdem::checkOutputFile(c.out);  // before minutes of packing, not after
    lsdem::PackingOptions& options = c.options;
    readContainer(c, options);
    if (c.seed < 0) throw Error("", "--seed wants a number >= 0");
    std::unique_ptr<tbb::global_control> limit;
    if (c.threads > 0)
        limit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, static_cast<size_t>(c.threads));
    options.mixture = readMixture(c);
    options.count = c.count;
    options.seed = static_cast<uint64_t>(c.seed);
    const char* container = options.cylinder ? "cylinder" : "box";
    const lsdem::PackingResult r =
        lsdem::generatePacking(options, [](const lsdem::PackingResult& p) {
            std::fprintf(stderr, "layer %d: %zu grains, solid fraction %.3f, %lld steps, %.1f s\n",
                         p.layers, p.scene.grains.size(), p.solidFraction, p.steps,
                         p.seconds);
        });
    const size_t placed = r.scene.grains.size();
    if (!r.complete) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "only %zu of %lld grains fit in the %s (solid fraction %.3f of its "
                      "volume)", placed, c.count, container, r.solidFraction);
        throw Error(c.out, text, std::string("enlarge the ") + container +
                                     ", or ask for at most " + std::to_string(placed) +
                                     " grains");
    }
    lsdem::writeGrainsCsv(r.scene, 0, placed, c.out);
    std::printf("packed %zu grains in %d layers (%lld steps, %.1f s, at most %lld grains per "
                "deposition): solid fraction %.4f, deepest overlap %.2g of the smaller "
                "bounding radius%s\nwrote %s\n",
                placed, r.layers, r.steps, r.seconds, r.largestLayerGrains, r.solidFraction,
                r.maxOverlap, r.unsettledLayers > 0 ? " (some layers not fully at rest)" : "",
                c.out.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app(
        "Fill a box or a vertical cylinder with a mixture of grain assets, without overlaps, "
        "and write\nthe packing as a grains CSV (asset, x, y, z, qw, qx, qy, qz) for a scene's "
        "[[grain_files]]\n(docs/packing.md).\n\n"
        "  lsdem-pack A.vdb [B.vdb ...] --count N --box X0 Y0 Z0 X1 Y1 Z1 -o packing.csv "
        "[options]\n"
        "  lsdem-pack --catalog assets/catalog.csv --set sand --count N "
        "--cylinder CX CY R Z0 Z1 -o packing.csv\n\n"
        "Grains are inserted at random in layers and deposited under gravity (along -z) until "
        "at rest;\nthe same seed gives the same file on any thread count. Lengths "
        "are the assets'.",
        "lsdem-pack");
    lsdem::cli::applyConventions(app);
    app.footer("Exit codes: 0 packed, 1 bad input or the count does not fit (the message says "
               "how many did),\n3 internal error.");
    PackCommandLine c;
    addOptions(app, c);

    return lsdem::cli::runTool("lsdem-pack", [&] {
        if (const auto exitCode = lsdem::cli::parse(app, argc, argv)) return *exitCode;
        return pack(c);
    });
}
