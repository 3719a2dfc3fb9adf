#include "lsdem/ls/BatchBake.h"

#include "AssetChecksum.h"
#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/ls/MassProperties.h"
#include "lsdem/mesh/MeshIO.h"
#include "lsdem/mesh/MeshValidation.h"
#include "lsdem/core/Sha256.h"
#include "lsdem/core/Stopwatch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

namespace lsdem {

namespace {

namespace fs = std::filesystem;

/// What happened to one file.
struct FileResult
{
    std::optional<CatalogEntry> entry;
    bool unchanged = false;
    std::string failure;
    std::vector<std::string> warnings;
};

/// Whether @a path is an asset file whose seal holds (one read and a SHA-256).
bool isIntactAsset(const std::string& path)
{
    try {
        verifyAssetFile(path);
        return true;
    } catch (const Error&) {
        return false;
    }
}

/// The earlier catalogue's rows by name, or none if there is no catalogue.
/// @throw Error if it cannot be read: the new catalogue would replace it with only this run's
/// rows, losing the others.
std::map<std::string, CatalogEntry> earlierRows(const std::string& catalogPath)
{
    std::map<std::string, CatalogEntry> rows;
    std::error_code ec;
    if (!fs::exists(catalogPath, ec)) return rows;
    try {
        for (CatalogEntry& e : readCatalog(catalogPath)) rows.emplace(e.name, std::move(e));
    } catch (const Error& e) {
        throw Error(e.where(),
                    "cannot read the existing catalogue (" + e.problem() +
                        "); nothing was baked, since a new catalogue would drop its other rows",
                    "correct that line, or move the catalogue away to start a new one");
    }
    return rows;
}

FileResult bakeOne(const std::string& path, const std::string& name,
                   const BatchBakeOptions& o, const std::string& optionsText,
                   const CatalogEntry* earlier)
{
    FileResult result;
    const std::string assetFile = name + ".vdb";
    const std::string assetPath = (fs::path(o.outDir) / assetFile).string();
    try {
        const Stopwatch clock;
        const std::string sha = sha256OfFile(path);
        std::error_code ec;
        if (earlier && !o.rebake && earlier->sourceSha256 == sha &&
            earlier->bakeOptions == optionsText && earlier->asset == assetFile &&
            fs::is_regular_file(assetPath, ec)) {
            // Only an intact asset is up to date: its seal is checked (a read and a SHA-256,
            // far cheaper than a bake); a truncated or changed one is baked again.
            try {
                verifyAssetFile(assetPath);
                result.entry = *earlier;
                result.entry->source = path;
                result.unchanged = true;
                return result;
            } catch (const Error& damaged) {
                result.warnings.push_back(damaged.where() + ": " + damaged.problem() +
                                          "; baking it again");
            }
        }
        TriangleMesh mesh = readMesh(path);
        BakeOptions bake = o.bake;
        if (o.voxelPerSize > 0.0 || o.nodeSpacingPerSize > 0.0) {
            // The size needs a solid: validate (and repair) here, and report the repairs here,
            // as bakeMesh finds nothing left to repair.
            appendRepairWarnings(validateSolidMesh(mesh, path), path, result.warnings);
            const double d = std::cbrt(6.0 * computeMassProperties(mesh).volume / kPi);
            if (o.voxelPerSize > 0.0) bake.voxelSize = o.voxelPerSize * d;
            if (o.nodeSpacingPerSize > 0.0) bake.nodeSpacing = o.nodeSpacingPerSize * d;
        }
        bake.optionsText = optionsText + " (voxel " + numberText(bake.voxelSize) +
                           (bake.nodePlacement == NodePlacement::Spacing
                                ? ", node spacing " + numberText(bake.nodeSpacing)
                                : std::string()) +
                           ")";
        GrainAsset asset = bakeMesh(std::move(mesh), path, bake, result.warnings);
        asset.provenance.sourceSha256 = sha;
        saveAsset(asset, assetPath);
        result.entry = catalogEntry(asset, name, assetFile, optionsText, clock.seconds());
    } catch (const Error& e) {
        result.failure = e.what();
    } catch (const std::exception& e) {
        // CGAL, OpenVDB or the allocator gave up on this file: the others may still bake.
        result.failure = path + ": internal error while baking: " + e.what();
    }
    return result;
}

} // namespace

std::string batchOptionsText(const BatchBakeOptions& o)
{
    const BakeOptions& b = o.bake;
    std::string text = o.voxelPerSize > 0.0 ? "voxel-per-size " + numberText(o.voxelPerSize)
                                            : "voxel " + numberText(b.voxelSize);
    switch (b.nodePlacement) {
    case NodePlacement::Spacing:
        text += o.nodeSpacingPerSize > 0.0
                    ? " node-spacing-per-size " + numberText(o.nodeSpacingPerSize)
                    : " node-spacing " + numberText(b.nodeSpacing);
        break;
    case NodePlacement::Count: text += " nodes " + std::to_string(b.nodeCount); break;
    case NodePlacement::MeshVertices: text += " mesh-nodes"; break;
    }
    text += b.areaRule == AreaRule::Mesh ? " areas mesh" : " areas uniform";
    // Always named: "auto" chose remeshing alone before the centroidal layout, so a catalogue
    // written then is baked again once rather than kept with the other layout's nodes.
    text += " node-layout " + nodeLayoutName(b.nodeLayout);
    text += " band " + std::to_string(b.exteriorBandVoxels);
    return text;
}

BatchBakeReport bakeBatch(const std::vector<std::string>& meshPaths,
                          const BatchBakeOptions& o, const BatchProgress& progress)
{
    if (meshPaths.empty()) throw Error("", "no mesh files to bake", "give one or more files");
    if (!(o.voxelPerSize >= 0.0) || !(o.nodeSpacingPerSize >= 0.0))
        throw Error("", "per-size voxel and node spacing must be positive");
    if (o.nodeSpacingPerSize > 0.0 && o.bake.nodePlacement != NodePlacement::Spacing)
        throw Error("", "a node spacing per size needs node placement by spacing");
    if (o.threads < 0) throw Error("", "--threads must be >= 0");
    // Names first: two files with one stem would overwrite each other's asset.
    std::vector<std::string> names;
    std::map<std::string, std::string> pathOfName;
    for (const std::string& p : meshPaths) {
        const std::string name = fs::path(p).stem().string();
        if (name.empty())
            throw Error(p, "cannot name an asset after this file (no file name)");
        const auto [it, fresh] = pathOfName.emplace(name, p);
        if (!fresh)
            throw Error(p, "has the same name '" + name + "' as " + it->second +
                               ": both would be baked to " + name + ".vdb",
                        "rename one of them, or bake them into different --out-dir folders");
        names.push_back(name);
    }
    prepareOutputFolder(o.outDir, "choose another --out-dir");

    BatchBakeReport report;
    report.catalogPath = (fs::path(o.outDir) / "catalog.csv").string();
    std::map<std::string, CatalogEntry> earlier = earlierRows(report.catalogPath);
    const std::string optionsText = batchOptionsText(o);

    std::vector<FileResult> results(meshPaths.size());
    std::mutex progressMutex;
    size_t done = 0;
    tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        // One file per task, handed out as threads free up (grains differ in cost).
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, meshPaths.size(), 1),
            [&](const tbb::blocked_range<size_t>& range) {
                for (size_t i = range.begin(); i != range.end(); ++i) {
                    const auto found = earlier.find(names[i]);
                    results[i] = bakeOne(meshPaths[i], names[i], o, optionsText,
                                         found == earlier.end() ? nullptr : &found->second);
                    std::lock_guard<std::mutex> lock(progressMutex);
                    ++done;
                    if (progress) progress(done, meshPaths.size(), meshPaths[i]);
                }
            },
            tbb::simple_partitioner());
    });

    for (size_t i = 0; i < results.size(); ++i) {
        FileResult& r = results[i];
        for (std::string& w : r.warnings) report.warnings.push_back(std::move(w));
        if (!r.entry) {
            // The earlier asset is untouched (saveAsset replaces a file only once it is
            // written): its row stays as long as the asset is intact (a damaged one would be
            // listed for simulations that cannot load it).
            report.failures.push_back({meshPaths[i], r.failure});
            const auto row = earlier.find(names[i]);
            if (row != earlier.end() &&
                !isIntactAsset((fs::path(o.outDir) / row->second.asset).string()))
                earlier.erase(row);
            continue;
        }
        earlier.erase(names[i]);  // this run's row replaces it
        (r.unchanged ? report.unchanged : report.baked) += 1;
        report.entries.push_back(std::move(*r.entry));
    }
    for (auto& [name, row] : earlier) {
        std::error_code ec;
        if (fs::is_regular_file(fs::path(o.outDir) / row.asset, ec))
            report.entries.push_back(std::move(row));
    }
    std::sort(report.entries.begin(), report.entries.end(),
              [](const CatalogEntry& a, const CatalogEntry& b) { return a.name < b.name; });
    writeCatalog(report.catalogPath, report.entries);
    return report;
}

} // namespace lsdem
