#include "lsdem/ls/Bake.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/ReleaseMemory.h"
#include "lsdem/ls/LevelSetGrid.h"
#include "lsdem/mesh/CentroidalNodes.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/ls/MeshLevelSet.h"
#include "lsdem/mesh/MeshRemesh.h"
#include "lsdem/mesh/MeshValidation.h"
#include "lsdem/core/Sha256.h"

#include <openvdb/tools/Dense.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace lsdem {

namespace {

std::string formatBytes(double bytes)
{
    std::ostringstream out;
    out.precision(3);
    if (bytes >= 1024.0 * 1024 * 1024) out << bytes / (1024.0 * 1024 * 1024) << " GiB";
    else out << bytes / (1024.0 * 1024) << " MiB";
    return out.str();
}

void checkOptions(const BakeOptions& o, const std::string& source)
{
    if (!(o.voxelSize > 0.0) || !std::isfinite(o.voxelSize))
        throw Error(source, "the voxel size (VDP) must be a positive finite length",
                    "give e.g. voxel 0.05 (lsdem-bake --voxel 0.05), in the mesh's length unit");
    if (o.nodePlacement == NodePlacement::Spacing &&
        (!(o.nodeSpacing > 0.0) || !std::isfinite(o.nodeSpacing)))
        throw Error(source, "the node spacing (SDP) must be a positive finite length",
                    "give e.g. node_spacing 0.1 (lsdem-bake --node-spacing 0.1), or nodes N, or "
                    "mesh_nodes");
    if (o.nodePlacement == NodePlacement::Count && o.nodeCount < 4)
        throw Error(source, "the node count must be at least 4",
                    "give e.g. nodes 2000 (lsdem-bake --nodes 2000)");
    // Analytic shapes are checked here too (meshLevelSet checks its own callers).
    if (o.exteriorBandVoxels < kMinExteriorBandVoxels ||
        o.exteriorBandVoxels > kMaxExteriorBandVoxels)
        throw Error(source,
                    "the exterior band must be " + std::to_string(kMinExteriorBandVoxels) +
                        " to " + std::to_string(kMaxExteriorBandVoxels) + " voxels wide, got " +
                        std::to_string(o.exteriorBandVoxels),
                    "give band 2 (lsdem-bake --band 2, the default) or more: interpolation near "
                    "the surface reads values up to 1.73 voxels outside it");
}

/// Refuse voxels too coarse for the shape, or grids that would not fit the memory budget.
void checkGridSize(const Vec3& extent, const BakeOptions& o, const std::string& source)
{
    const double thinnest = extent.minCoeff();
    if (o.voxelSize * 4.0 > thinnest) {
        std::ostringstream msg;
        msg << "the voxel size " << o.voxelSize << " is too coarse for a shape whose thinnest "
            << "extent is " << thinnest << " (fewer than 4 voxels across)";
        // (A suggestion, so six significant digits: 0.035, not 0.034999999999999996.)
        std::ostringstream fix;
        fix << "use voxel " << thinnest / 20.0 << " or smaller to resolve the shape (20 voxels "
            << "across; " << thinnest / 4.0 << " is the coarsest accepted) (lsdem-bake --voxel; "
            << "check the mesh's length unit)";
        throw Error(source, msg.str(), fix.str());
    }
    // Peak memory is about one float and one index per voxel of the padded bounding box.
    double voxels = 1.0;
    for (int k = 0; k < 3; ++k)
        voxels *= extent[k] / o.voxelSize + 2.0 * (o.exteriorBandVoxels + 2);
    const double bytes = voxels * 8.0;
    if (bytes > o.memoryBudgetBytes) {
        std::ostringstream msg;
        msg << "a level set at voxel size " << o.voxelSize << " would need about "
            << formatBytes(bytes) << " (" << voxels << " voxels), over the memory budget of "
            << formatBytes(o.memoryBudgetBytes);
        throw Error(source, msg.str(),
                    "use a larger voxel, or raise the memory budget (lsdem-bake "
                    "--memory-budget-gb) if the machine has room");
    }
}

/// Refuse a node spacing that would place more than kMaxNodeCount nodes on a surface of area
/// @a area: remeshing to it would run away in memory, and a box's face grid would overflow.
void checkNodeSpacing(double area, const BakeOptions& o, const std::string& source)
{
    if (o.nodePlacement != NodePlacement::Spacing) return;
    const double finest = edgeLengthForNodeCount(area, kMaxNodeCount);
    if (o.nodeSpacing < finest) {
        std::ostringstream msg, fix;
        msg << "a node spacing of " << o.nodeSpacing << " would place about "
            << nodeCountForEdgeLength(area, o.nodeSpacing)
            << " nodes on a surface of area " << area << ", over the limit of "
            << double(kMaxNodeCount);
        fix << "use node_spacing " << finest << " or larger (lsdem-bake --node-spacing; check "
            << "the mesh's length unit), or nodes N";
        throw Error(source, msg.str(), fix.str());
    }
}

/// The sharp-edge angle of the remesher's feature edges: a mesh with none gets centroidal nodes.
const double kSharpEdgeDeg = RemeshOptions{}.featureAngleDeg;

/// Nodes at the centroids of a centroidal Voronoi tessellation of @a mesh, each with its
/// cell's area and mean normal; none if cells reach across parts thinner than the node
/// spacing (more than 0.1 % of the surface owned across: its traction would push the wrong
/// way, and a cell straddling a thin rim can have no mean normal at all), which the
/// remesher, following the mesh's edges, does not misread. Exactly the count asked, unless
/// two nodes fell on one point (the second is dropped: never seen).
SurfaceNodes centroidalNodes(const TriangleMesh& mesh, const BakeOptions& o)
{
    const double area = surfaceArea(mesh);
    // As many nodes as equilateral triangles of edge SDP would have (each vertex owns two).
    const size_t count =
        o.nodePlacement == NodePlacement::Count
            ? size_t(o.nodeCount)
            : size_t(std::max(4.0, std::round(nodeCountForEdgeLength(area, o.nodeSpacing))));
    const CentroidalNodes placed = placeCentroidalNodes(mesh, count);
    SurfaceNodes nodes;
    double facingAway = 0.0;
    for (size_t i = 0; i < placed.positions.size(); ++i) {
        const RestrictedVoronoiCell& cell = placed.cells[i];
        facingAway += cell.facingAway;
        if (!(cell.area > 0.0)) continue;  // (two nodes at one point: the first owns it)
        if (!(cell.normalArea.norm() > 1e-6 * cell.area)) return {};
        nodes.positions.push_back(placed.positions[i]);
        nodes.normals.push_back(cell.normalArea.normalized());
        nodes.areas.push_back(cell.area);
    }
    if (facingAway > 1e-3 * area) return {};
    if (o.areaRule == AreaRule::Uniform) {
        const double mean = nodes.totalArea() / double(nodes.size());
        std::fill(nodes.areas.begin(), nodes.areas.end(), mean);
    }
    return nodes;
}

} // namespace

std::string nodeLayoutName(NodeLayout layout)
{
    switch (layout) {
    case NodeLayout::Automatic: return "auto";
    case NodeLayout::Remesh: return "remesh";
    case NodeLayout::Centroidal: return "centroidal";
    }
    return "auto";
}

NodeLayout nodeLayoutNamed(const std::string& name)
{
    for (NodeLayout layout : {NodeLayout::Automatic, NodeLayout::Remesh, NodeLayout::Centroidal})
        if (nodeLayoutName(layout) == name) return layout;
    throw Error("", "the node layout must be 'auto', 'remesh' or 'centroidal', got '" + name + "'",
                "give --node-layout auto (centroidal unless the mesh has sharp edges), remesh "
                "or centroidal");
}

TriangleMesh nodeSurface(const TriangleMesh& surface, const BakeOptions& o, bool keepFineInput)
{
    RemeshOptions remesh;
    remesh.keepFineInput = keepFineInput;
    if (o.nodePlacement == NodePlacement::Spacing) {
        remesh.targetEdgeLength = o.nodeSpacing;
        return remeshIsotropic(surface, remesh);
    }
    // For a node count: the remesher's result moves in steps with the target length, so
    // correct the length by the square root of the count ratio (count ∝ 1/h²) a few times and
    // keep the closest result.
    const int wanted = o.nodeCount;
    remesh.targetEdgeLength = edgeLengthForNodeCount(surfaceArea(surface), wanted);
    TriangleMesh best;
    for (int attempt = 0; attempt < 6; ++attempt) {
        TriangleMesh candidate = remeshIsotropic(surface, remesh);
        const double count = double(candidate.vertices.size());
        if (best.vertices.empty() ||
            std::abs(count - wanted) < std::abs(double(best.vertices.size()) - wanted))
            best = std::move(candidate);
        if (std::abs(count - wanted) <= 0.03 * wanted) break;
        remesh.targetEdgeLength *= std::sqrt(count / wanted);
    }
    return best;
}

SurfaceNodes placeNodesOnMesh(const TriangleMesh& mesh, const BakeOptions& o,
                              std::vector<std::string>* warnings, std::string* layoutUsed)
{
    auto used = [layoutUsed](const char* layout) {
        if (layoutUsed) *layoutUsed = layout;
    };
    if (o.nodePlacement == NodePlacement::MeshVertices) {
        used("mesh vertices");
        return nodesFromMesh(mesh, o.areaRule);
    }
    const bool automatic = o.nodeLayout == NodeLayout::Automatic;
    const SharpEdges sharp = automatic ? countSharpEdges(mesh, kSharpEdgeDeg) : SharpEdges();
    // A scan's noise turns edges sharp at random; the remesher would keep every one, slowly.
    const bool noise = automatic && sharpEdgesLookLikeNoise(sharp);
    if (o.nodeLayout == NodeLayout::Centroidal || (automatic && (sharp.edges == 0 || noise))) {
        SurfaceNodes nodes = centroidalNodes(mesh, o);
        if (!nodes.positions.empty()) {
            if (warnings && noise && sharp.edges >= kManySharpEdges)
                warnings->push_back(
                    "the mesh's " + std::to_string(sharp.edges) + " sharp edges (over " +
                    std::to_string(int(kSharpEdgeDeg)) + " degrees) look like a scan's noise (" +
                    std::to_string(sharp.looseEnds) + " loose ends, where a shape's edges "
                    "would run on in lines to its corners), so its nodes are spread evenly "
                    "(centroidal); to keep them as features, bake with --node-layout remesh "
                    "(node_layout = \"remesh\"): slower");
            used("centroidal");
            return nodes;
        }
        if (warnings)
            warnings->push_back("the mesh has parts thinner than the node spacing, across "
                                "which the centroidal layout's cells would reach, so its nodes "
                                "are remeshed instead (the node count is then about, not "
                                "exactly, the one asked)");
    }
    // Thousands of sharp edges in lines: a shape's edges, each kept as a feature (slowly).
    if (warnings && automatic && !noise && sharp.edges >= kManySharpEdges)
        warnings->push_back(
            "the mesh has " + std::to_string(sharp.edges) + " sharp edges (over " +
            std::to_string(int(kSharpEdgeDeg)) + " degrees) in lines, so its nodes are "
            "remeshed with each kept as a feature; if they are a scan's noise, bake with "
            "--node-layout centroidal (node_layout = \"centroidal\"): faster, and nodes "
            "evenly spread over the surface");
    used("remesh");
    return nodesFromMesh(nodeSurface(mesh, o, /*keepFineInput=*/true), o.areaRule);
}

namespace {

/// Mark @a grid as a level set and wrap it with its index-space origin and voxel size.
std::shared_ptr<const LevelSetGrid> wrapLevelSet(const openvdb::FloatGrid::Ptr& grid,
                                                 const Vec3& origin, double voxelSize)
{
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    auto levelSet = std::make_shared<LevelSetGrid>();
    levelSet->grid = toLevelSetGrid(*grid);
    levelSet->origin = origin;
    levelSet->voxelSize = voxelSize;
    return levelSet;
}

/// Shared by both bake paths once nodes and the level set exist.
void finishAsset(GrainAsset& asset, const BakeOptions& o, std::vector<std::string>& warnings)
{
    // Z-order at about half the node spacing, so runs of consecutive nodes are compact patches
    // (the culling blocks) at every scale; the cell is the 8-voxel leaf halved until it is that
    // fine, so the nodes within one leaf's width still come together.
    const double patch = std::sqrt(std::max(asset.nodes.totalArea(), 1e-300) /
                                   double(std::max<size_t>(asset.nodes.size(), 1)));
    double cell = 8.0 * o.voxelSize;
    while (cell > 0.5 * patch) cell *= 0.5;
    sortNodesSpatially(asset.nodes, cell);
    deriveContactBounds(asset);
    asset.areaRule = o.areaRule;
    asset.spacing = nodeSpacing(asset.nodes);
    asset.voxelSize = o.voxelSize;
    asset.exteriorBandVoxels = o.exteriorBandVoxels;
    for (const Vec3& p : asset.nodes.positions)
        asset.boundingRadius = std::max(asset.boundingRadius, p.norm());
    asset.provenance.options = o.optionsText;
    asset.provenance.lsdemVersion = LSDEM_VERSION;
    if (asset.spacing.mean < 0.5 * o.voxelSize) {
        std::ostringstream msg;
        msg << "the node spacing (mean " << asset.spacing.mean << ") is less than half the "
            << "voxel size " << o.voxelSize << ": the level set cannot resolve what the nodes "
            << "sample; a voxel about 0.4x the node spacing is the converged ratio";
        warnings.push_back(msg.str());
    }
}

} // namespace

GrainAsset bakeMeshFile(const std::string& meshPath, const BakeOptions& options,
                        std::vector<std::string>& warnings)
{
    checkOptions(options, meshPath);
    TriangleMesh mesh = readMesh(meshPath);
    GrainAsset asset = bakeMesh(std::move(mesh), meshPath, options, warnings);
    asset.provenance.sourceSha256 = sha256OfFile(meshPath);
    return asset;
}

GrainAsset bakeMesh(TriangleMesh mesh, const std::string& sourceName, const BakeOptions& options,
                    std::vector<std::string>& warnings)
{
    checkOptions(options, sourceName);
    appendRepairWarnings(validateSolidMesh(mesh, sourceName), sourceName, warnings);
    releaseFreedMemory();  // (the validation's lists, for the stages' threads to take)
    checkNodeSpacing(surfaceArea(mesh), options, sourceName);

    // Move the mesh to its principal frame: centroid at the origin, principal axes along x,y,z.
    const MassProperties inputProps = computeMassProperties(mesh);
    GrainAsset asset;
    asset.inputFrame = principalFrame(inputProps, mesh);
    transformMesh(mesh, asset.inputFrame.rotation,
                  -(asset.inputFrame.rotation * asset.inputFrame.centroid));
    const auto bounds = meshBounds(mesh);
    checkGridSize(bounds[1] - bounds[0], options, sourceName);

    asset.mass.volume = inputProps.volume;
    asset.mass.inertia = asset.inputFrame.moments.asDiagonal();
    asset.provenance.source = sourceName;

    // The node surface, then the level set of the input surface (the geometric truth), one
    // after the other, each threaded within. Side by side their peaks added (each stage's is
    // 1.5-3 times the grid's size); one after the other a bake takes 0-16 % longer on 2 cores
    // (docs/assets.md, "Cost"), and a batch bakes several files side by side anyway.
    asset.nodes = placeNodesOnMesh(mesh, options, &warnings, &asset.provenance.nodeLayout);
    releaseFreedMemory();
    asset.levelSet = meshLevelSet(mesh, options.voxelSize, options.exteriorBandVoxels);
    finishAsset(asset, options, warnings);
    for (const Vec3& v : mesh.vertices)
        asset.boundingRadius = std::max(asset.boundingRadius, v.norm());
    return asset;
}

GrainAsset bakeAnalytic(const AnalyticShape& shape, const BakeOptions& options,
                        std::vector<std::string>& warnings)
{
    const std::string source = shape.describe();
    checkOptions(options, source);
    if (options.nodePlacement == NodePlacement::MeshVertices)
        throw Error(source, "--mesh-nodes needs an input mesh, and an analytic shape has none",
                    "use --node-spacing SDP or --nodes N");
    const Vec3 half = shape.halfExtents();
    checkGridSize(2.0 * half, options, source);
    checkNodeSpacing(shape.surfaceArea(), options, source);

    GrainAsset asset;
    asset.mass = shape.massProperties();
    asset.inputFrame.moments = asset.mass.inertia.diagonal();
    asset.provenance.source = source;

    // Exact signed distance at every voxel of the padded box; values beyond the exterior band
    // equal the background and are left inactive.
    initializeOpenVdb();
    const double vox = options.voxelSize;
    const float background = float(options.exteriorBandVoxels * vox);
    Eigen::Vector3i count;
    for (int k = 0; k < 3; ++k)
        count[k] = int(std::ceil(half[k] / vox)) + options.exteriorBandVoxels + 1;
    const Vec3 origin = -vox * count.cast<double>();
    const openvdb::CoordBBox box(openvdb::Coord(0), openvdb::Coord(2 * count.x(), 2 * count.y(),
                                                                  2 * count.z()));
    openvdb::tools::Dense<float, openvdb::tools::LayoutZYX> dense(box);
    tbb::parallel_for(0, 2 * count.x() + 1, [&](int i) {
        for (int j = 0; j <= 2 * count.y(); ++j)
            for (int k = 0; k <= 2 * count.z(); ++k) {
                const Vec3 p = origin + vox * Vec3(i, j, k);
                const double d = shape.signedDistance(p);
                dense.setValue(i, j, k, d >= background ? background : float(d));
            }
    });
    auto grid = openvdb::FloatGrid::create(background);
    openvdb::tools::copyFromDense(dense, *grid, /*tolerance=*/0.0f);
    grid->setTransform(makeGridTransform(vox, origin));
    asset.levelSet = wrapLevelSet(grid, origin, vox);

    // Nodes: a box keeps its structured face grids (edges and corners exact); curved shapes
    // are remeshed isotropically and projected back onto the exact surface.
    TriangleMesh surface;
    if (shape.kind == AnalyticShape::Kind::Box) {
        const double h = options.nodePlacement == NodePlacement::Count
                             ? std::sqrt(shape.surfaceArea() / options.nodeCount)
                             : options.nodeSpacing;
        surface = shape.surfaceMesh(h);
        asset.provenance.nodeLayout = "face grids";
    } else {
        const double h = options.nodePlacement == NodePlacement::Count
                             ? edgeLengthForNodeCount(shape.surfaceArea(), options.nodeCount)
                             : options.nodeSpacing;
        surface = nodeSurface(shape.surfaceMesh(0.5 * h), options, false);  // fine seed
        for (Vec3& v : surface.vertices) v = shape.closestSurfacePoint(v);
        asset.provenance.nodeLayout = "remesh, projected";
    }
    asset.nodes = nodesFromMesh(surface, options.areaRule);
    for (size_t i = 0; i < asset.nodes.size(); ++i)
        asset.nodes.normals[i] = shape.outwardNormal(asset.nodes.positions[i]);
    finishAsset(asset, options, warnings);
    return asset;
}

} // namespace lsdem
