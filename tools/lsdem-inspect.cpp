/// lsdem-inspect: look inside a grain asset or any level-set .vdb.

#include "common/CommandLine.h"

#include "lsdem/ls/Error.h"
#include "lsdem/ls/Inspection.h"
#include "lsdem/ls/LevelSetSampler.h"
#include "lsdem/ls/MeshIO.h"
#include "lsdem/ls/SlicePlot.h"

#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

namespace {

const char* const kUsage = R"(usage: lsdem-inspect FILE.vdb [--json] [--sample X Y Z]...
                     [--slice AXIS=VALUE --png OUT.png] [--mesh OUT.obj|.stl|.ply]

Prints a summary of a grain asset (or of the first level-set grid of any .vdb): grid size and
memory, node count and spacing, node-area sum against the level set's own area and volume,
mass properties, and quality (|φ| at the nodes, share of band voxels with |∇φ| off 1 by >10 %).

  --json               print the summary as JSON instead of text
  --sample X Y Z       print φ and ∇φ (trilinear interpolant) at a point of the asset frame
  --slice AXIS=VALUE   with --png: draw φ on the plane x=, y= or z=VALUE, zero contour, nodes
  --png OUT.png        where to write the slice picture
  --mesh OUT           write the zero isosurface as a triangle mesh (.obj, .stl, .ply)
)";

std::string jsonNumber(double v)
{
    if (!std::isfinite(v)) return "null";
    std::ostringstream out;
    out.precision(12);
    out << v;
    return out.str();
}

std::string jsonString(const std::string& s)
{
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\', out += c;
        else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else out += c;
    }
    return out + "\"";
}

std::string jsonVec(const lsdem::Vec3& v)
{
    return "[" + jsonNumber(v.x()) + ", " + jsonNumber(v.y()) + ", " + jsonNumber(v.z()) + "]";
}

void printJson(const lsdem::InspectionTarget& t, const lsdem::InspectionReport& r)
{
    std::ostringstream o;
    o << "{\n  \"file\": " << jsonString(t.path) << ",\n  \"grid\": " << jsonString(t.gridName)
      << ",\n  \"lsdem_asset\": " << (t.asset ? "true" : "false")
      << ",\n  \"voxel_size\": " << jsonNumber(r.voxelSize)
      << ",\n  \"index_min\": [" << r.indexMin[0] << ", " << r.indexMin[1] << ", " << r.indexMin[2]
      << "],\n  \"index_max\": [" << r.indexMax[0] << ", " << r.indexMax[1] << ", "
      << r.indexMax[2] << "],\n  \"world_min\": " << jsonVec(r.worldMin)
      << ",\n  \"world_max\": " << jsonVec(r.worldMax)
      << ",\n  \"active_voxels\": " << r.activeVoxels
      << ",\n  \"memory_bytes\": " << jsonNumber(r.memoryBytes)
      << ",\n  \"dense_bytes\": " << jsonNumber(r.denseBytes)
      << ",\n  \"background\": " << jsonNumber(r.background)
      << ",\n  \"level_set_area\": " << jsonNumber(r.levelSetArea)
      << ",\n  \"level_set_volume\": " << jsonNumber(r.levelSetVolume)
      << ",\n  \"band_voxels\": " << r.bandVoxels
      << ",\n  \"band_gradient_off_share\": " << jsonNumber(r.bandGradientOffShare);
    if (t.asset) {
        const auto& a = *t.asset;
        o << ",\n  \"node_count\": " << r.nodeCount
          << ",\n  \"node_spacing\": {\"mean\": " << jsonNumber(r.spacing.mean)
          << ", \"min\": " << jsonNumber(r.spacing.min) << ", \"max\": "
          << jsonNumber(r.spacing.max) << "}"
          << ",\n  \"node_area_sum\": " << jsonNumber(r.nodeAreaSum)
          << ",\n  \"area_rule\": " << jsonString(a.areaRule == lsdem::AreaRule::Mesh ? "mesh" : "uniform")
          << ",\n  \"max_abs_phi_at_nodes_voxels\": " << jsonNumber(r.maxAbsPhiAtNodesVoxels)
          << ",\n  \"volume\": " << jsonNumber(a.mass.volume)
          << ",\n  \"centroid\": " << jsonVec(a.mass.centroid)
          << ",\n  \"principal_moments\": " << jsonVec(a.mass.inertia.diagonal())
          << ",\n  \"input_centroid\": " << jsonVec(a.inputFrame.centroid)
          << ",\n  \"input_to_asset_rotation\": [" << jsonVec(a.inputFrame.rotation.row(0))
          << ", " << jsonVec(a.inputFrame.rotation.row(1)) << ", "
          << jsonVec(a.inputFrame.rotation.row(2)) << "]"
          << ",\n  \"bounding_radius\": " << jsonNumber(a.boundingRadius)
          << ",\n  \"source\": " << jsonString(a.provenance.source)
          << ",\n  \"source_sha256\": " << jsonString(a.provenance.sourceSha256)
          << ",\n  \"bake_options\": " << jsonString(a.provenance.options)
          << ",\n  \"lsdem_version\": " << jsonString(a.provenance.lsdemVersion);
    }
    o << "\n}\n";
    std::cout << o.str();
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
        std::printf("  count             %zu\n", r.nodeCount);
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

} // namespace

int main(int argc, char** argv)
{
    using namespace lsdem;
    return cli::runTool("lsdem-inspect", [&]() -> int {
        cli::Arguments args(argc, argv);
        std::string path, pngPath, meshPath;
        std::optional<SliceSpec> slice;
        std::vector<Vec3> samples;
        bool json = false;
        if (args.done()) {
            std::cerr << kUsage;
            return 2;
        }
        while (!args.done()) {
            const std::string a = args.next();
            if (a == "-h" || a == "--help") {
                std::cout << kUsage;
                return 0;
            } else if (a == "--json") {
                json = true;
            } else if (a == "--sample") {
                const double x = args.number(a), y = args.number(a), z = args.number(a);
                samples.emplace_back(x, y, z);
            } else if (a == "--slice") {
                slice = parseSliceSpec(args.value(a));
            } else if (a == "--png") {
                pngPath = args.value(a);
            } else if (a == "--mesh") {
                meshPath = args.value(a);
            } else if (!a.empty() && a[0] == '-') {
                throw Error("", "unknown option '" + a + "'", "see lsdem-inspect --help");
            } else {
                if (!path.empty()) throw Error("", "more than one input file");
                path = a;
            }
        }
        if (path.empty()) throw Error("", "no input file", "see lsdem-inspect --help");
        if (slice.has_value() != !pngPath.empty())
            throw Error("", "--slice and --png go together",
                        "e.g. --slice z=0 --png slice.png");

        const InspectionTarget target = openForInspection(path);
        if (!samples.empty()) {
            LevelSetSampler sampler(*target.levelSet);
            for (const Vec3& p : samples) {
                const LevelSetSample s = sampler.sample(p);
                if (json)
                    std::printf("{\"point\": %s, \"phi\": %s, \"gradient\": %s}\n",
                                jsonVec(p).c_str(), jsonNumber(s.phi).c_str(),
                                jsonVec(s.gradient).c_str());
                else
                    std::printf("phi(%.6g, %.6g, %.6g) = %.8g   grad = (%.6g, %.6g, %.6g)\n",
                                p.x(), p.y(), p.z(), s.phi, s.gradient.x(), s.gradient.y(),
                                s.gradient.z());
            }
        }
        if (slice) {
            writeSlicePng(target, *slice, pngPath);
            if (!json) std::printf("wrote %s\n", pngPath.c_str());
        }
        if (!meshPath.empty()) {
            writeMesh(zeroIsosurface(*target.levelSet), meshPath);
            if (!json) std::printf("wrote %s\n", meshPath.c_str());
        }
        if (samples.empty() && !slice && meshPath.empty()) {
            const InspectionReport report = inspect(target);
            if (json) printJson(target, report);
            else printText(target, report);
        }
        return 0;
    });
}
