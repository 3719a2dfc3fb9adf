/// lsdem-pack: fill a box with a mixture of grain assets (random insertion, then deposition
/// under gravity) and write the packing as a grains CSV that a scene reads with [[grain_files]].

#include "common/CommandLine.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Error.h"
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

int main(int argc, char** argv)
{
    using lsdem::Error;
    CLI::App app(
        "Fill a box with a mixture of grain assets, without overlaps, and write the packing as "
        "a grains\nCSV (asset, x, y, z, qw, qx, qy, qz) for a scene's [[grain_files]] "
        "(docs/packing.md).\n\n"
        "  lsdem-pack A.vdb [B.vdb ...] --count N --box X0 Y0 Z0 X1 Y1 Z1 -o packing.csv "
        "[options]\n\n"
        "Grains are inserted at random in layers and deposited under gravity (along -z) until "
        "at rest;\nthe same seed gives the same file on any thread count. Lengths "
        "are the assets'.",
        "lsdem-pack");
    lsdem::cli::applyConventions(app);
    app.footer("Exit codes: 0 packed, 1 bad input or the count does not fit (the message says "
               "how many did),\n3 internal error.");
    std::vector<std::string> files, names;
    std::vector<double> fractions, box;
    long long count = 0, seed = 1, threads = 0;
    std::string out;
    lsdem::PackingOptions options;
    app.add_option("assets", files, "grain assets baked by lsdem-bake")->type_name("ASSET.vdb");
    lsdem::cli::addNumbers(app, "--fractions", fractions,
                           "share of the grain count per asset (default: equal)");
    app.add_option("--names", names,
                   "asset names written in the CSV, as the scene's [assets.NAME]\n(default: "
                   "the file names without .vdb)")
        ->type_name("NAME");
    lsdem::cli::addInteger(app, "--count", count, "grains to pack");
    lsdem::cli::addNumbers(app, "--box", box, "the inside of the box: min and max corners", 6);
    lsdem::cli::addInteger(app, "--seed", seed, "random seed (positions, orientations, order)");
    lsdem::cli::addNumber(app, "--friction", options.friction,
                          "Coulomb friction during deposition (0: densest packing)");
    lsdem::cli::addNumber(app, "--settle", options.settleTolerance,
                          "at rest when kinetic energy < this x sum of m*g*d");
    app.add_option("-o,--out", out, "the grains CSV to write (atomically)")->type_name("FILE");
    lsdem::cli::addInteger(app, "--threads", threads, "worker threads (default: all cores)");

    return lsdem::cli::runTool("lsdem-pack", [&] {
        if (const auto exitCode = lsdem::cli::parse(app, argc, argv)) return *exitCode;
        if (files.empty()) throw Error("", "no grain assets given", "give one or more .vdb files");
        if (out.empty()) throw Error("", "no output file given", "pass -o packing.csv");
        if (box.size() != 6) throw Error("", "no box given", "pass --box X0 Y0 Z0 X1 Y1 Z1");
        if (!fractions.empty() && fractions.size() != files.size())
            throw Error("", "--fractions has " + std::to_string(fractions.size()) +
                                " values for " + std::to_string(files.size()) + " assets",
                        "give one fraction per asset");
        if (!names.empty() && names.size() != files.size())
            throw Error("", "--names has " + std::to_string(names.size()) + " names for " +
                                std::to_string(files.size()) + " assets",
                        "give one name per asset");
        if (seed < 0) throw Error("", "--seed wants a number >= 0");
        if (threads < 0) throw Error("", "--threads wants a number >= 1");
        std::unique_ptr<tbb::global_control> limit;
        if (threads > 0)
            limit = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
        for (size_t k = 0; k < files.size(); ++k) {
            lsdem::PackingComponent c;
            c.name = names.empty() ? std::filesystem::path(files[k]).stem().string() : names[k];
            c.asset = lsdem::loadAsset(files[k]);
            c.fraction = fractions.empty() ? 1.0 : fractions[k];
            options.mixture.push_back(c);
        }
        options.boxMin = lsdem::Vec3(box[0], box[1], box[2]);
        options.boxMax = lsdem::Vec3(box[3], box[4], box[5]);
        options.count = count;
        options.seed = static_cast<uint64_t>(seed);
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
                          "only %zu of %lld grains fit in the box (solid fraction %.3f of its "
                          "volume)", placed, count, r.solidFraction);
            throw Error(out, text, "enlarge the box, or ask for at most " +
                                       std::to_string(placed) + " grains");
        }
        lsdem::writeGrainsCsv(r.scene, 0, placed, out);
        std::printf("packed %zu grains in %d layers (%lld steps, %.1f s): solid fraction %.4f, "
                    "deepest overlap %.2g of the smaller bounding radius%s\nwrote %s\n",
                    placed, r.layers, r.steps, r.seconds, r.solidFraction, r.maxOverlap,
                    r.unsettledLayers > 0 ? " (some layers not fully at rest)" : "",
                    out.c_str());
        return 0;
    });
}
