#include "lsdem/ls/AssetIO.h"

#include "AssetChecksum.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetGrid.h"

#include <openvdb/io/File.h>
#include <openvdb/points/PointAttribute.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

namespace lsdem {

namespace {

const int kFormatVersion = 2;  // 2: sealed with a SHA-256 (AssetChecksum.h)
const char* const kLevelSetGridName = "phi";
const char* const kNodesGridName = "nodes";

openvdb::Vec3d toVdb(const Vec3& v) { return openvdb::Vec3d(v.x(), v.y(), v.z()); }
Vec3 fromVdb(const openvdb::Vec3d& v) { return Vec3(v.x(), v.y(), v.z()); }

std::string areaRuleName(AreaRule rule) { return rule == AreaRule::Mesh ? "mesh" : "uniform"; }

void writeMetadata(openvdb::GridBase& grid, const GrainAsset& asset)
{
    grid.insertMeta("lsdem_format", openvdb::StringMetadata(kAssetFormatName));
    grid.insertMeta("lsdem_format_version", openvdb::Int32Metadata(kFormatVersion));
    grid.insertMeta("lsdem_version", openvdb::StringMetadata(asset.provenance.lsdemVersion));
    grid.insertMeta("source", openvdb::StringMetadata(asset.provenance.source));
    grid.insertMeta("source_sha256", openvdb::StringMetadata(asset.provenance.sourceSha256));
    grid.insertMeta("bake_options", openvdb::StringMetadata(asset.provenance.options));
    grid.insertMeta("node_layout", openvdb::StringMetadata(asset.provenance.nodeLayout));
    grid.insertMeta("voxel_size", openvdb::DoubleMetadata(asset.voxelSize));
    grid.insertMeta("grid_origin", openvdb::Vec3DMetadata(toVdb(asset.levelSet->origin)));
    grid.insertMeta("exterior_band_voxels", openvdb::Int32Metadata(asset.exteriorBandVoxels));
    grid.insertMeta("volume", openvdb::DoubleMetadata(asset.mass.volume));
    grid.insertMeta("centroid", openvdb::Vec3DMetadata(toVdb(asset.mass.centroid)));
    for (int r = 0; r < 3; ++r)
        grid.insertMeta("inertia_row" + std::to_string(r),
                        openvdb::Vec3DMetadata(toVdb(asset.mass.inertia.row(r).transpose())));
    grid.insertMeta("input_centroid", openvdb::Vec3DMetadata(toVdb(asset.inputFrame.centroid)));
    for (int r = 0; r < 3; ++r)
        grid.insertMeta("input_to_asset_row" + std::to_string(r),
                        openvdb::Vec3DMetadata(
                            toVdb(asset.inputFrame.rotation.row(r).transpose())));
    grid.insertMeta("principal_moments", openvdb::Vec3DMetadata(toVdb(asset.inputFrame.moments)));
    grid.insertMeta("area_rule", openvdb::StringMetadata(areaRuleName(asset.areaRule)));
    grid.insertMeta("node_count", openvdb::Int64Metadata(int64_t(asset.nodes.size())));
    grid.insertMeta("node_spacing_mean", openvdb::DoubleMetadata(asset.spacing.mean));
    grid.insertMeta("node_spacing_min", openvdb::DoubleMetadata(asset.spacing.min));
    grid.insertMeta("node_spacing_max", openvdb::DoubleMetadata(asset.spacing.max));
    grid.insertMeta("bounding_radius", openvdb::DoubleMetadata(asset.boundingRadius));
}

template <typename T>
T readMeta(const openvdb::GridBase& grid, const std::string& key, const std::string& path)
{
    try {
        return grid.metaValue<T>(key);
    } catch (const openvdb::Exception&) {
        throw Error(path, "grid '" + grid.getName() + "' lacks the lsdem metadata '" + key + "'",
                    "the file is not a complete lsdem asset; bake it again with lsdem-bake");
    }
}

Vec3 readVec3(const openvdb::GridBase& grid, const std::string& key, const std::string& path)
{
    return fromVdb(readMeta<openvdb::Vec3d>(grid, key, path));
}

openvdb::points::PointDataGrid::Ptr makeNodesGrid(const GrainAsset& asset)
{
    using namespace openvdb;
    const size_t n = asset.nodes.size();
    std::vector<Vec3d> positions(n), normals(n);
    std::vector<double> areas(n);
    std::vector<int32_t> ids(n);
    for (size_t i = 0; i < n; ++i) {
        positions[i] = toVdb(asset.nodes.positions[i]);
        normals[i] = toVdb(asset.nodes.normals[i]);
        areas[i] = asset.nodes.areas[i];
        ids[i] = int32_t(i);
    }
    // Points bucket into voxels of a few node spacings; the exact values live in attributes
    // (P itself is stored as voxel offsets, which is enough for viewers). The voxels start
    // below the lowest node: centred on the origin, the nodes would straddle OpenVDB's eight
    // top-level nodes, and reading each means going through its 32³ table of tiles (a quarter
    // of a small asset's load).
    const double pointVoxel = std::max(asset.voxelSize, 2.0 * asset.spacing.mean);
    Vec3d lowest(std::numeric_limits<double>::infinity());
    for (const Vec3d& p : positions) lowest = math::minComponent(lowest, p);
    const auto xform = math::Transform::createLinearTransform(pointVoxel);
    if (n > 0) xform->postTranslate(lowest - Vec3d(pointVoxel));
    points::PointAttributeVector<Vec3d> positionWrapper(positions);
    auto indexGrid = tools::createPointIndexGrid<tools::PointIndexGrid>(positionWrapper, *xform);
    auto grid = points::createPointDataGrid<points::NullCodec, points::PointDataGrid>(
        *indexGrid, positionWrapper, *xform);
    auto& tree = grid->tree();
    points::appendAttribute<Vec3d>(tree, "position");
    points::appendAttribute<Vec3d>(tree, "normal");
    points::appendAttribute<double>(tree, "area");
    points::appendAttribute<int32_t>(tree, "node_id");
    points::populateAttribute(tree, indexGrid->tree(), "position", positionWrapper);
    points::populateAttribute(tree, indexGrid->tree(), "normal",
                              points::PointAttributeVector<Vec3d>(normals));
    points::populateAttribute(tree, indexGrid->tree(), "area",
                              points::PointAttributeVector<double>(areas));
    points::populateAttribute(tree, indexGrid->tree(), "node_id",
                              points::PointAttributeVector<int32_t>(ids));
    grid->setName(kNodesGridName);
    return grid;
}

SurfaceNodes readNodesGrid(const openvdb::points::PointDataGrid& grid, size_t count,
                           NodeNormals normals, const std::string& path)
{
    using namespace openvdb;
    // The count is metadata: check it against the grid before allocating for it.
    const Index64 stored = points::pointCount(grid.tree());
    if (stored != count)
        throw Error(path, "the nodes grid holds " + std::to_string(stored) + " nodes but the " +
                              "metadata says " + std::to_string(count),
                    "the file is corrupt; bake the asset again");
    SurfaceNodes nodes;
    nodes.positions.assign(count, Vec3::Zero());
    const bool keepNormals = normals == NodeNormals::Load;
    if (keepNormals) nodes.normals.assign(count, Vec3::Zero());
    nodes.areas.assign(count, 0.0);
    std::vector<char> seen(count, 0);
    size_t found = 0;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const auto& descriptor = leaf->attributeSet().descriptor();
        for (const char* name : {"position", "normal", "area", "node_id"})
            if (descriptor.find(name) == points::AttributeSet::INVALID_POS)
                throw Error(path, std::string("the nodes grid lacks the attribute '") + name + "'",
                            "bake the asset again with lsdem-bake");
        // A handle of the wrong value type throws; a short array would be read past its end.
        std::unique_ptr<points::AttributeHandle<Vec3d>> position, normal;
        std::unique_ptr<points::AttributeHandle<double>> area;
        std::unique_ptr<points::AttributeHandle<int32_t>> id;
        try {
            position = std::make_unique<points::AttributeHandle<Vec3d>>(
                leaf->constAttributeArray("position"));
            normal = std::make_unique<points::AttributeHandle<Vec3d>>(
                leaf->constAttributeArray("normal"));
            area = std::make_unique<points::AttributeHandle<double>>(
                leaf->constAttributeArray("area"));
            id = std::make_unique<points::AttributeHandle<int32_t>>(
                leaf->constAttributeArray("node_id"));
        } catch (const openvdb::Exception& e) {
            throw Error(path, std::string("the nodes grid has attributes of the wrong type (") +
                                  e.what() + ")",
                        "bake the asset again with lsdem-bake");
        }
        const Index64 inLeaf = leaf->pointCount();
        if (position->size() < inLeaf || normal->size() < inLeaf || area->size() < inLeaf ||
            id->size() < inLeaf)
            throw Error(path, "the nodes grid has attribute arrays shorter than its points",
                        "the file is corrupt; bake the asset again");
        for (auto index = leaf->beginIndexOn(); index; ++index) {
            const int32_t i = id->get(*index);
            if (i < 0 || size_t(i) >= count || seen[i])
                throw Error(path, "the nodes grid has a bad or repeated node_id " +
                                      std::to_string(i),
                            "the file is corrupt; bake the asset again");
            seen[i] = 1;
            ++found;
            nodes.positions[i] = fromVdb(position->get(*index));
            if (keepNormals) nodes.normals[i] = fromVdb(normal->get(*index));
            nodes.areas[i] = area->get(*index);
        }
    }
    if (found != count)
        throw Error(path, "the nodes grid holds " + std::to_string(found) + " nodes but the " +
                              "metadata says " + std::to_string(count),
                    "the file is corrupt; bake the asset again");
    return nodes;
}

} // namespace

void saveAsset(const GrainAsset& asset, const std::string& path)
{
    initializeOpenVdb();
    if (!asset.levelSet || !asset.levelSet->grid)
        throw Error(path, "the asset has no level set to write");
    if (!asset.nodes.hasNormals())
        throw Error(path, "the asset's nodes have no normals (a simulation's copy holds none)",
                    "save the asset it was loaded or baked from");
    // The stored values as a standard FloatGrid (a fresh copy: metadata is set on it).
    openvdb::FloatGrid::Ptr phi = toFloatGrid(*asset.levelSet->grid);
    phi->setName(kLevelSetGridName);
    phi->setGridClass(openvdb::GRID_LEVEL_SET);
    writeMetadata(*phi, asset);
    openvdb::GridPtrVec grids{phi, makeNodesGrid(asset)};
    writeFileAtomically(path, [&](const std::string& tmp) {
        try {
            openvdb::MetaMap fileMeta;
            fileMeta.insertMeta(kAssetChecksumKey,
                                openvdb::StringMetadata(unsealedAssetChecksum()));
            openvdb::io::File file(tmp);
            file.write(grids, fileMeta);
            file.close();
        } catch (const openvdb::Exception& e) {
            throw Error(path, std::string("OpenVDB could not write the file: ") + e.what());
        }
        sealAssetFile(tmp, path);
    });
}

namespace {

/// The level set and the nodes grid of the asset file at @a path.
struct AssetGrids
{
    openvdb::FloatGrid::Ptr phi;
    openvdb::points::PointDataGrid::Ptr nodes;
};

AssetGrids readAssetGrids(const std::string& path)
{
    openvdb::GridPtrVecPtr grids;
    try {
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        grids = file.getGrids();
        file.close();
    } catch (const std::exception& e) {
        throw Error(path, std::string("not a readable OpenVDB file (") + e.what() + ")",
                    "the file is corrupt or not a .vdb; bake it again with lsdem-bake");
    }

    AssetGrids g;
    for (const auto& grid : *grids) {
        if (grid->getName() == kLevelSetGridName)
            g.phi = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
        else if (grid->getName() == kNodesGridName)
            g.nodes = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(grid);
    }
    if (!g.phi)
        throw Error(path, "holds no float grid named 'phi'",
                    "this is not an lsdem asset; bake one with lsdem-bake (lsdem-inspect can "
                    "still summarise any level-set .vdb)");
    return g;
}

/// The asset format and version @a phi declares must be this lsdem's; the nodes grid must be
/// there and the transform a uniform linear map.
void checkAssetFormat(const AssetGrids& g, const std::string& path)
{
    const std::string format = readMeta<std::string>(*g.phi, "lsdem_format", path);
    const int version = readMeta<int32_t>(*g.phi, "lsdem_format_version", path);
    if (format != kAssetFormatName || version != kFormatVersion)
        throw Error(path, "is an asset of format '" + format + "' version " +
                              std::to_string(version) + "; this lsdem reads version " +
                              std::to_string(kFormatVersion),
                    "bake the asset again with this lsdem");
    if (!g.nodes)
        throw Error(path, "holds no points grid named 'nodes'", "bake the asset again");
    const auto& xform = g.phi->transform();
    if (!xform.isLinear() || !xform.hasUniformScale())
        throw Error(path, "the level set's transform is not a uniform linear map",
                    "bake the asset again with lsdem-bake");
}

/// The level set of @a phi with its exact voxel size and origin, which are kept as metadata
/// (the transform's matrix would round them) and must agree with the transform OpenVDB tools use.
std::shared_ptr<LevelSetGrid> readLevelSet(const openvdb::FloatGrid& phi, const std::string& path)
{
    const auto& xform = phi.transform();
    auto levelSet = std::make_shared<LevelSetGrid>();
    levelSet->voxelSize = readMeta<double>(phi, "voxel_size", path);
    levelSet->origin = readVec3(phi, "grid_origin", path);
    if (!(levelSet->voxelSize > 0.0 && std::isfinite(levelSet->voxelSize)) ||
        !levelSet->origin.allFinite())
        throw Error(path, "the voxel size or the grid origin is not a finite length",
                    "the file is corrupt; bake the asset again");
    levelSet->grid = toLevelSetGrid(phi);
    const Vec3 transformOrigin = fromVdb(xform.indexToWorld(openvdb::Vec3d(0, 0, 0)));
    if (std::abs(xform.voxelSize()[0] - levelSet->voxelSize) > 1e-9 * levelSet->voxelSize ||
        (transformOrigin - levelSet->origin).norm() > 1e-6 * levelSet->voxelSize)
        throw Error(path, "the level set's transform disagrees with its lsdem metadata",
                    "the file was edited or is corrupt; bake the asset again");
    return levelSet;
}

/// The asset's properties kept as metadata of @a phi: mass properties, its input frame, how
/// its nodes were placed, its provenance.
void readAssetMetadata(const openvdb::FloatGrid& phi, GrainAsset& asset, const std::string& path)
{
    asset.exteriorBandVoxels = readMeta<int32_t>(phi, "exterior_band_voxels", path);
    asset.mass.volume = readMeta<double>(phi, "volume", path);
    asset.mass.centroid = readVec3(phi, "centroid", path);
    for (int r = 0; r < 3; ++r)
        asset.mass.inertia.row(r) =
            readVec3(phi, "inertia_row" + std::to_string(r), path).transpose();
    asset.inputFrame.centroid = readVec3(phi, "input_centroid", path);
    for (int r = 0; r < 3; ++r)
        asset.inputFrame.rotation.row(r) =
            readVec3(phi, "input_to_asset_row" + std::to_string(r), path).transpose();
    asset.inputFrame.moments = readVec3(phi, "principal_moments", path);
    const std::string rule = readMeta<std::string>(phi, "area_rule", path);
    asset.areaRule = rule == "uniform" ? AreaRule::Uniform : AreaRule::Mesh;
    asset.spacing.mean = readMeta<double>(phi, "node_spacing_mean", path);
    asset.spacing.min = readMeta<double>(phi, "node_spacing_min", path);
    asset.spacing.max = readMeta<double>(phi, "node_spacing_max", path);
    asset.boundingRadius = readMeta<double>(phi, "bounding_radius", path);
    asset.provenance.lsdemVersion = readMeta<std::string>(phi, "lsdem_version", path);
    asset.provenance.source = readMeta<std::string>(phi, "source", path);
    asset.provenance.sourceSha256 = readMeta<std::string>(phi, "source_sha256", path);
    asset.provenance.options = readMeta<std::string>(phi, "bake_options", path);
    // Recorded since 2026-11-28: an earlier asset has none (and stays valid).
    if (const auto layout = phi.getMetadata<openvdb::StringMetadata>("node_layout"))
        asset.provenance.nodeLayout = layout->value();
}

} // namespace

std::shared_ptr<const GrainAsset> loadAsset(const std::string& path, NodeNormals normals)
{
    initializeOpenVdb();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw Error(path, "no such file", "check the path; bake assets with lsdem-bake");
    if (std::filesystem::is_directory(path, ec))
        throw Error(path, "is a folder, not an asset file");
    // OpenVDB believes the sizes a file states; only a file that is byte for byte as written
    // reaches it.
    verifyAssetFile(path);
    const AssetGrids grids = readAssetGrids(path);
    checkAssetFormat(grids, path);
    const openvdb::FloatGrid& phi = *grids.phi;
    auto asset = std::make_shared<GrainAsset>();
    asset->levelSet = readLevelSet(phi, path);
    asset->voxelSize = asset->levelSet->voxelSize;
    readAssetMetadata(phi, *asset, path);
    const int64_t count = readMeta<int64_t>(phi, "node_count", path);
    if (count <= 0) throw Error(path, "the asset has no surface nodes", "bake it again");
    asset->nodes = readNodesGrid(*grids.nodes, size_t(count), normals, path);
    deriveContactBounds(*asset);
    return asset;
}

std::shared_ptr<const GrainAsset> AssetLibrary::get(const std::string& path)
{
    std::error_code ec;
    std::string key = std::filesystem::weakly_canonical(path, ec).string();
    if (ec) key = path;
    std::lock_guard<std::mutex> lock(mMutex);
    auto it = mAssets.find(key);
    if (it != mAssets.end()) return it->second;
    auto asset = loadAsset(path);
    mAssets.emplace(key, asset);
    return asset;
}

size_t AssetLibrary::size() const
{
    std::lock_guard<std::mutex> lock(mMutex);
    return mAssets.size();
}

} // namespace lsdem
