/// lsdem-inspect: look inside a grain asset or any level-set .vdb.

#include "common/CommandLine.h"

#include "lsdem/core/Error.h"
#include "lsdem/ls/Inspection.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/ls/SlicePlot.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::ordered_json;

/// A number as JSON: non-finite values (which JSON cannot hold) become null.
Json number(double v)
{
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

Json vec(const lsdem::Vec3& v)
{
    return Json::array({number(v.x()), number(v.y()), number(v.z())});
}

/// @a json as text; doubles are written to round-trip exactly, and bytes of a file name that
/// are not UTF-8 are replaced rather than refused.
std::string text(const Json& json, int indent)
{
    return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

void printJson(const lsdem::InspectionTarget& t, const lsdem::InspectionReport& r)
{
    Json o;
    o["file"] = t.path;
    o["grid"] = t.gridName;
    o["lsdem_asset"] = bool(t.asset);
    o["voxel_size"] = number(r.voxelSize);
    o["index_min"] = r.indexMin;
    o["index_max"] = r.indexMax;
    o["world_min"] = vec(r.worldMin);
    o["world_max"] = vec(r.worldMax);
    o["active_voxels"] = r.activeVoxels;
    o["memory_bytes"] = number(r.memoryBytes);
    o["dense_bytes"] = number(r.denseBytes);
    o["background"] = number(r.background);
    o["level_set_area"] = number(r.levelSetArea);
    o["level_set_volume"] = number(r.levelSetVolume);
    o["band_voxels"] = r.bandVoxels;
    o["band_gradient_off_share"] = number(r.bandGradientOffShare);
    if (t.asset) {
        const auto& a = *t.asset;
        o["node_count"] = r.nodeCount;
        o["node_spacing"] = {{"mean", number(r.spacing.mean)},
                             {"min", number(r.spacing.min)},
                             {"max", number(r.spacing.max)}};
        o["node_area_sum"] = number(r.nodeAreaSum);
        o["area_rule"] = a.areaRule == lsdem::AreaRule::Mesh ? "mesh" : "uniform";
        o["node_layout"] = a.provenance.nodeLayout;
        o["max_abs_phi_at_nodes_voxels"] = number(r.maxAbsPhiAtNodesVoxels);
        o["volume"] = number(a.mass.volume);
        o["centroid"] = vec(a.mass.centroid);
        o["principal_moments"] = vec(a.mass.inertia.diagonal());
        o["input_centroid"] = vec(a.inputFrame.centroid);
        o["input_to_asset_rotation"] =
            Json::array({vec(a.inputFrame.rotation.row(0)), vec(a.inputFrame.rotation.row(1)),
                         vec(a.inputFrame.rotation.row(2))});
        o["bounding_radius"] = number(a.boundingRadius);
        o["source"] = a.provenance.source;
        o["source_sha256"] = a.provenance.sourceSha256;
        o["bake_options"] = a.provenance.options;
        o["lsdem_version"] = a.provenance.lsdemVersion;
    }
    std::cout << text(o, 2) << "\n";
}

void printText(const lsdem::InspectionTarget& t, const lsdem::InspectionReport& r)
{
    const double mib = 1024.0 * 1024.0;
    std::printf("%s  (%s, grid '%s')\n", t.path.c_str(),
                t.asset ? "lsdem grain asset" : "foreign level set", t.gridName.c_str());
    std::printf("grid\n");
    std::printf("  voxel size        %.6g\n", r.voxelSize);
    std::printf("  index bounds      [%d %d %d] .. [%d %d %d]\n", r.indexMin[0], r.indexMin[1],
                r.indexMin[2], r.indexMax[0], r.indexMax[1], r.indexMax[2]);
    std::printf("  world bounds      [%.5g %.5g %.5g] .. [%.5g %.5g %.5g]\n", r.worldMin.x(),
                r.worldMin.y(), r.worldMin.z(), r.worldMax.x(), r.worldMax.y(), r.worldMax.z());
    std::printf("  active voxels     %lld\n", r.activeVoxels);
    std::printf("  memory            %.3f MiB (a dense float grid of the same bounds: %.3f MiB)\n",
                r.memoryBytes / mib, r.denseBytes / mib);
    std::printf("  exterior band     %.5g (%.3g voxels)\n", r.background,
                r.background / r.voxelSize);
    std::printf("level set (OpenVDB LevelSetMeasure)\n");
    std::printf("  area              %.6g\n", r.levelSetArea);
    std::printf("  volume            %.6g\n", r.levelSetVolume);
    if (t.asset) {
        const auto& a = *t.asset;
        std::printf("nodes\n");
        std::printf("  count             %zu (%s)\n", r.nodeCount,
                    a.provenance.nodeLayout.empty() ? "layout not recorded"
                                                    : a.provenance.nodeLayout.c_str());
        std::printf("  spacing           mean %.5g, min %.5g, max %.5g (VDP/SDP = %.3f)\n",
                    r.spacing.mean, r.spacing.min, r.spacing.max, r.voxelSize / r.spacing.mean);
        std::printf("  area sum          %.6g (%s rule; level set area %+.3f %%)\n", r.nodeAreaSum,
                    a.areaRule == lsdem::AreaRule::Mesh ? "mesh" : "uniform",
                    r.levelSetArea > 0 ? 100.0 * (r.nodeAreaSum / r.levelSetArea - 1.0) : 0.0);
        std::printf("mass properties (unit density, asset frame)\n");
        std::printf("  volume            %.6g\n", a.mass.volume);
        std::printf("  centroid          %.3g %.3g %.3g\n", a.mass.centroid.x(),
                    a.mass.centroid.y(), a.mass.centroid.z());
        std::printf("  principal moments %.6g %.6g %.6g\n", a.mass.inertia(0, 0),
                    a.mass.inertia(1, 1), a.mass.inertia(2, 2));
        std::printf("  input centroid    %.6g %.6g %.6g\n", a.inputFrame.centroid.x(),
                    a.inputFrame.centroid.y(), a.inputFrame.centroid.z());
        std::printf("provenance\n");
        std::printf("  source            %s\n", a.provenance.source.c_str());
        if (!a.provenance.sourceSha256.empty())
            std::printf("  sha256            %s\n", a.provenance.sourceSha256.c_str());
        std::printf("  options           %s\n", a.provenance.options.c_str());
        std::printf("  lsdem             %s\n", a.provenance.lsdemVersion.c_str());
    }
    std::printf("quality\n");
    if (t.asset)
        std::printf("  max |phi| at nodes          %.3g voxels\n", r.maxAbsPhiAtNodesVoxels);
    std::printf("  band voxels |grad phi| off 1 by > 10 %%: %.2f %% of %lld\n",
                100.0 * r.bandGradientOffShare, r.bandVoxels);
}

/// φ and ∇φ at each point of @a samples (x, y, z in turn), as text or JSON Lines.
void printSamples(const lsdem::InspectionTarget& target, const std::vector<double>& samples,
                  bool json)
{
    using namespace lsdem;
    if (samples.empty()) return;
    LevelSetSampler sampler(*target.levelSet);
    for (size_t i = 0; i + 2 < samples.size(); i += 3) {
        const Vec3 p(samples[i], samples[i + 1], samples[i + 2]);
        const LevelSetSample s = sampler.sample(p);
        if (json)
            std::cout << text({{"point", vec(p)}, {"phi", number(s.phi)}, {"gradient", vec(s.gradient)}},
                              -1)
                      << "\n";
        else
            std::printf("phi(%.6g, %.6g, %.6g) = %.8g   grad = (%.6g, %.6g, %.6g)\n", p.x(), p.y(),
                        p.z(), s.phi, s.gradient.x(), s.gradient.y(), s.gradient.z());
    }
}
} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    CLI::App app("Prints a summary of a grain asset (or of the first level-set grid of any .vdb): "
                 "grid size and\nmemory, node count and spacing, node-area sum against the level "
                 "set's own area and volume,\nmass properties, and quality (|φ| at the nodes, "
                 "share of band voxels with |∇φ| off 1 by >10 %).",
                 "lsdem-inspect");
    cli::applyConventions(app);
    app.footer("Lengths are in the asset's own unit. Exit codes: 0 done, 1 bad input, 2 no "
               "arguments (this\nhelp on stderr), 3 internal error.");
    std::vector<std::string> paths;
    std::string slice, pngPath, meshPath;
    std::vector<double> samples;
    bool json = false;
    app.add_option("file", paths, "the asset or level set to inspect")->type_name("FILE.vdb");
    app.add_flag("--json", json,
                 "print the summary as one JSON object instead of text, or the samples\n"
                 "as JSON Lines (one object per --sample, a line each)");
    cli::addNumbers(app, "--sample", samples,
                    "print φ and ∇φ (trilinear interpolant) at a point of the asset\n"
                    "frame; may be repeated",
                    3)
        ->option_text("X Y Z")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--slice", slice,
                   "with --png: draw φ on the plane x=, y= or z=VALUE, the zero\n"
                   "contour and the nodes")
        ->type_name("AXIS=VALUE");
    app.add_option("--png", pngPath, "where to write the slice picture")->type_name("OUT.png");
    app.add_option("--mesh", meshPath,
                   "write the zero isosurface as a triangle mesh (.obj, .stl, .ply)")
        ->type_name("OUT");
    if (argc < 2) {
        std::cerr << app.help();
        return 2;
    }
    return cli::runTool("lsdem-inspect", [&]() -> int {
        if (const auto exitCode = cli::parse(app, argc, argv)) return *exitCode;
        if (paths.size() > 1) throw Error("", "more than one input file");
        const std::optional<SliceSpec> sliceSpec =
            slice.empty() ? std::nullopt : std::optional<SliceSpec>(parseSliceSpec(slice));
        if (paths.empty()) throw Error("", "no input file", "see lsdem-inspect --help");
        if (sliceSpec.has_value() != !pngPath.empty())
            throw Error("", "--slice and --png go together",
                        "e.g. --slice z=0 --png slice.png");
        cli::refuseOutputOverInput(pngPath, "--png", paths);
        cli::refuseOutputOverInput(meshPath, "--mesh", paths);

        const InspectionTarget target = openForInspection(paths[0]);
        printSamples(target, samples, json);
        if (sliceSpec) {
            writeSlicePng(target, *sliceSpec, pngPath);
            if (!json) std::printf("wrote %s\n", pngPath.c_str());
        }
        if (!meshPath.empty()) {
            writeMesh(zeroIsosurface(*target.levelSet), meshPath);
            if (!json) std::printf("wrote %s\n", meshPath.c_str());
        }
        if (samples.empty() && !sliceSpec && meshPath.empty()) {
            const InspectionReport report = inspect(target);
            if (json) printJson(target, report);
            else printText(target, report);
        }
        return 0;
    });
}
