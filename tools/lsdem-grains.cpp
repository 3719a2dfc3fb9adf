/// lsdem-grains: sand-like grain meshes without scans (see GrainGenerator.h): star-shaped
/// surfaces from spherical harmonics with a power-law spectrum, reproducible from a seed.

#include "common/CommandLine.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainGenerator.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace {

constexpr long long kLargestFirst = 1000000000000000LL;

struct GrainsCommandLine
{
    lsdem::GrainShapeOptions shape;
    long long count = 10;
    long long seed = 1;
    long long first = 0;
    std::string format = "stl";
    std::string prefix = "grain_";
    std::string outDir;
    bool quiet = false;
};

void addOptions(CLI::App& app, GrainsCommandLine& c)
{
    using lsdem::cli::addInteger;
    using lsdem::cli::addNumber;
    const std::string set = "The set";
    addInteger(app, "--count", c.count, "number of grains")->type_name("N")->group(set);
    addInteger(app, "--seed", c.seed, "random seed: the same seed gives the same files")
        ->type_name("S")
        ->group(set);
    addInteger(app, "--first", c.first,
               "index of the first grain (grain i is the same in every run)")
        ->type_name("I")
        ->group(set);

    const std::string shape = "Shape";
    addNumber(app, "--elongation", c.shape.elongation,
              "intermediate / long axis of the base ellipsoid, (0, 1]")
        ->type_name("E")
        ->group(shape);
    addNumber(app, "--flatness", c.shape.flatness,
              "short / intermediate axis of the base ellipsoid, (0, 1]")
        ->type_name("F")
        ->group(shape);
    addNumber(app, "--roughness", c.shape.roughness,
              "RMS of the log-radius perturbation (0: an ellipsoid)")
        ->type_name("R")
        ->group(shape);
    addNumber(app, "--decay", c.shape.decay,
              "degree-l amplitude ~ l^-decay (small: angular grains)")
        ->type_name("D")
        ->group(shape);
    addInteger(app, "--max-degree", c.shape.maxDegree, "highest spherical-harmonic degree")
        ->type_name("L")
        ->group(shape);

    const std::string size = "Size and mesh";
    addNumber(app, "--size", c.shape.size,
              "median equivalent diameter (sphere of equal volume), length")
        ->type_name("D")
        ->group(size);
    addNumber(app, "--size-spread", c.shape.sizeSpread,
              "standard deviation of ln(diameter); 0: all equal")
        ->type_name("S")
        ->group(size);
    addInteger(app, "--triangles", c.shape.triangles, "about this many triangles per grain")
        ->type_name("N")
        ->group(size);

    const std::string output = "Output";
    app.add_option("--out-dir", c.outDir, "folder for the mesh files (created if missing)")
        ->type_name("DIR")
        ->group(output);
    app.add_option("--format", c.format, "'stl' (binary) or 'obj' (text, 7 digits)")
        ->type_name("FMT")
        ->capture_default_str()
        ->group(output);
    app.add_option("--prefix", c.prefix, "file name prefix (files are PREFIX0000.stl, ...)")
        ->type_name("P")
        ->capture_default_str()
        ->group(output);
    app.add_flag("-q,--quiet", c.quiet, "print nothing but errors")->group(output);
}

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    CLI::App app(
        "Generates sand-like grain meshes: closed, manifold, outward triangle meshes of\n"
        "star-shaped surfaces r(θ,φ) = exp(Σ a_lm Y_lm) (real spherical harmonics of degree 2\n"
        "to L, amplitudes falling as a power of the degree), stretched to the given elongation\n"
        "and flatness and scaled to an equivalent diameter. The same seed and options give\n"
        "byte-identical files; grain i does not depend on --count.\n\n"
        "  lsdem-grains --count 50 --seed 1 --out-dir grains/",
        "lsdem-grains");
    cli::applyConventions(app);
    app.footer("Lengths are in your unit (e.g. mm); bake the files with lsdem-bake --out-dir.\n"
               "Exit codes: 0 written, 1 bad input, 2 no arguments (this help on stderr), "
               "3 internal error.");
    GrainsCommandLine c;
    addOptions(app, c);
    if (argc < 2) {
        std::cerr << app.help();
        return 2;
    }
    return cli::runTool("lsdem-grains", [&]() -> int {
        if (const auto exitCode = cli::parse(app, argc, argv)) return *exitCode;
        if (c.outDir.empty()) throw Error("", "no output folder", "add --out-dir DIR");
        if (c.count < 1 || c.count > 10000000)
            throw Error("", "--count wants 1 to 1e7 grains, got " + std::to_string(c.count));
        // (Bounded so that first + count cannot overflow.)
        if (c.first < 0 || c.first > kLargestFirst)
            throw Error("", "--first must be from 0 to 1e15, got " + std::to_string(c.first));
        if (c.seed < 0) throw Error("", "--seed must be >= 0");
        if (c.format != "stl" && c.format != "obj")
            throw Error("", "--format wants 'stl' or 'obj', got '" + c.format + "'");
        if (c.prefix.find('/') != std::string::npos)
            throw Error("", "--prefix must not hold '/'", "choose the folder with --out-dir");
        checkGrainShapeOptions(c.shape);
        prepareOutputFolder(c.outDir, "choose another --out-dir");

        // Grain i is always named with at least four digits, whatever --first and --count, so
        // that sets made in chunks name their grains (and so their assets) alike.
        constexpr int digits = 4;
        const long long last = c.first + c.count - 1;
        for (long long i = c.first; i <= last; ++i) {
            const TriangleMesh mesh = generateGrain(c.shape, uint64_t(c.seed), uint64_t(i));
            char number[32];
            std::snprintf(number, sizeof number, "%0*lld", digits, i);
            const std::string path =
                (std::filesystem::path(c.outDir) / (c.prefix + number + "." + c.format)).string();
            writeGrainMesh(mesh, path);
        }
        if (!c.quiet)
            std::printf("wrote %lld grains (%s%0*lld.%s ... %s%0*lld.%s) to %s\n", c.count,
                        c.prefix.c_str(), digits, c.first, c.format.c_str(), c.prefix.c_str(),
                        digits, last, c.format.c_str(), c.outDir.c_str());
        return 0;
    });
}
