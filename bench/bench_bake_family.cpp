// The bake on a family of meshes none of which was tuned on (MeshFamily.h), whole and by
// stage. Part of bench_libls; run only these with
//   build/bench/bench_libls --benchmark_filter=Family --benchmark_repetitions=3
// The bake benchmarks report wall time ("Time") and the CPU time of all threads ("CPU").

#include "lsdem/ls/Bake.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/ls/MeshLevelSet.h"
#include "lsdem/mesh/CentroidalNodes.h"
#include "lsdem/mesh/MeshRemesh.h"
#include "lsdem/mesh/MeshValidation.h"

#include "MeshFamily.h"
#include "ProcessMemory.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace lsdem;
using namespace lsdem::bench;

namespace {

/// Member @a index in its principal frame, as bakeMesh has it before its stages (made once).
const FamilyMesh& framedMember(int index)
{
    static std::map<int, FamilyMesh> made;
    auto found = made.find(index);
    if (found != made.end()) return found->second;
    FamilyMesh member = familyMesh(index);
    const PrincipalFrame frame = principalFrame(computeMassProperties(member.mesh), member.mesh);
    transformMesh(member.mesh, frame.rotation, -(frame.rotation * frame.centroid));
    return made.emplace(index, std::move(member)).first->second;
}

/// The whole bake; arg 2 the layout (0 auto, the default; 1 centroidal, as a noisy scan is
/// best given).
void BM_BakeFamily(benchmark::State& state)
{
    const FamilyMesh member = familyMesh(int(state.range(0)));
    BakeOptions o = familyBakeOptions();
    o.nodeLayout = state.range(1) == 0 ? NodeLayout::Automatic : NodeLayout::Centroidal;
    double peak = 0, grid = 0, nodes = 0, spacing = 0, area = 0;
    for (auto _ : state) {
        std::vector<std::string> warnings;
        TriangleMesh input = member.mesh;  // the input, resident before as a reader leaves it
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        const GrainAsset asset = bakeMesh(std::move(input), member.name, o, warnings);
        peak = statusBytes("VmHWM") - before;
        grid = double(asset.levelSet->grid->memUsage());
        nodes = double(asset.nodes.size());
        spacing = asset.spacing.mean;
        area = asset.nodes.totalArea();
    }
    state.SetLabel(member.name + (state.range(1) == 0 ? "" : " centroidal"));
    state.counters["triangles"] = double(member.mesh.triangles.size());
    // What `auto` decides on: the sharp edges and their loose ends (CentroidalNodes.h).
    const SharpEdges sharp = countSharpEdges(member.mesh, RemeshOptions{}.featureAngleDeg);
    state.counters["sharp_edges"] = double(sharp.edges);
    state.counters["loose_ends"] = double(sharp.looseEnds);
    state.counters["nodes"] = nodes;
    // The SDP asks for nodes as on equilateral triangles of edge SDP: 2A/(√3·SDP²).
    state.counters["nodes_over_asked"] =
        nodes / (2.0 * area / (std::sqrt(3.0) * o.nodeSpacing * o.nodeSpacing));
    state.counters["mean_spacing"] = spacing;
    state.counters["peak_over_grid"] = peak / grid;
}
BENCHMARK(BM_BakeFamily)->ArgsProduct({benchmark::CreateDenseRange(0, kFamilySize - 1, 1), {0}})
    ->Args({kFamilySize - 1, 1})->Unit(benchmark::kMillisecond)
    ->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

/// The node stage alone, by layout (arg 2: 0 remeshing, 1 centroidal), with the spread of
/// the nodes' areas and nearest-neighbour distances (relative standard deviations).
void BM_BakeFamilyNodes(benchmark::State& state)
{
    const FamilyMesh& member = framedMember(int(state.range(0)));
    BakeOptions o = familyBakeOptions();
    o.nodeLayout = state.range(1) == 0 ? NodeLayout::Remesh : NodeLayout::Centroidal;
    SurfaceNodes nodes;
    double peak = 0;
    for (auto _ : state) {
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        nodes = placeNodesOnMesh(member.mesh, o);
        peak = statusBytes("VmHWM") - before;
    }
    auto relativeSpread = [](const std::vector<double>& values) {
        double sum = 0, sum2 = 0;
        for (double v : values) sum += v, sum2 += v * v;
        const double mean = sum / double(values.size());
        return std::sqrt(std::max(0.0, sum2 / double(values.size()) - mean * mean)) / mean;
    };
    const double area = surfaceArea(member.mesh);
    state.SetLabel(member.name + (state.range(1) == 0 ? " remesh" : " centroidal"));
    state.counters["nodes"] = double(nodes.size());
    state.counters["area_error"] = nodes.totalArea() / area - 1.0;
    state.counters["area_spread"] = relativeSpread(nodes.areas);
    state.counters["spacing_min_over_mean"] = nodeSpacing(nodes).min / nodeSpacing(nodes).mean;
    state.counters["peak_MiB"] = peak / kMiB;
}
BENCHMARK(BM_BakeFamilyNodes)->ArgsProduct({benchmark::CreateDenseRange(0, kFamilySize - 1, 1), {0, 1}})
    ->Unit(benchmark::kMillisecond)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

/// The validation alone (the bake's first step), on a copy of the member as read.
void BM_BakeFamilyValidation(benchmark::State& state)
{
    const FamilyMesh& member = framedMember(int(state.range(0)));
    double peak = 0;
    for (auto _ : state) {
        warmUpProcess();
        TriangleMesh input = member.mesh;
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        benchmark::DoNotOptimize(validateSolidMesh(input, member.name));
        peak = statusBytes("VmHWM") - before;
    }
    state.SetLabel(member.name);
    state.counters["peak_MiB"] = peak / kMiB;
    state.counters["peak_bytes_per_triangle"] = peak / double(member.mesh.triangles.size());
}
BENCHMARK(BM_BakeFamilyValidation)->DenseRange(0, kFamilySize - 1)->Unit(benchmark::kMillisecond)
    ->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

void BM_BakeFamilyLevelSet(benchmark::State& state)
{
    const FamilyMesh& member = framedMember(int(state.range(0)));
    const BakeOptions o = familyBakeOptions();
    double peak = 0, grid = 0;
    for (auto _ : state) {
        warmUpProcess();
        resetPeakRss();
        const double before = statusBytes("VmRSS");
        const auto levelSet = meshLevelSet(member.mesh, o.voxelSize, o.exteriorBandVoxels);
        peak = statusBytes("VmHWM") - before;
        grid = double(levelSet->grid->memUsage());
    }
    state.SetLabel(member.name);
    state.counters["grid_MiB"] = grid / kMiB;
    state.counters["peak_over_grid"] = peak / grid;
}
BENCHMARK(BM_BakeFamilyLevelSet)->DenseRange(0, kFamilySize - 1)->Unit(benchmark::kMillisecond)
    ->Iterations(1)->MeasureProcessCPUTime()->UseRealTime();

} // namespace
