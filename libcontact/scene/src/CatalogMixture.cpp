#include "lsdem/scene/CatalogMixture.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainCatalog.h"
#include "lsdem/core/RunInParallel.h"

#include <filesystem>

namespace lsdem {

namespace {

/// Where the row @a e of @a catalog points: relative asset paths are the catalogue's folder's,
/// as the scene reader resolves them.
std::filesystem::path assetFileOf(const std::string& catalog, const CatalogEntry& e)
{
    namespace fs = std::filesystem;
    return fs::path(e.asset).is_absolute() ? fs::path(e.asset)
                                           : fs::path(catalog).parent_path() / e.asset;
}

} // namespace

std::vector<std::string> catalogAssetFiles(const std::string& catalog)
{
    std::error_code notFound;
    if (!std::filesystem::is_regular_file(catalog, notFound)) return {};
    std::vector<std::string> files;
    for (const CatalogEntry& e : readCatalog(catalog))
        files.push_back(assetFileOf(catalog, e).string());
    return files;
}

std::vector<PackingComponent> catalogMixture(const std::string& catalog,
                                             const std::string& setName)
{
    namespace fs = std::filesystem;
    if (setName.empty() || setName.find('/') != std::string::npos)
        throw Error("", "the asset set's name '" + setName + "' must be non-empty and hold no '/'",
                    "give the name of the scene's [asset_sets.NAME] that reads the catalogue, "
                    "e.g. --set sand");
    std::error_code notFound;  // a regular file only: a folder is no catalogue
    if (!fs::is_regular_file(catalog, notFound))
        throw Error(catalog, "catalogue not found",
                    "give the catalog.csv that lsdem-bake --out-dir DIR wrote in DIR");
    const std::vector<CatalogEntry> entries = readCatalog(catalog);
    if (entries.empty())
        throw Error(catalog, "the catalogue lists no assets",
                    "bake some files into its folder with lsdem-bake --out-dir");
    const std::string rebake = "run the lsdem-bake --out-dir batch that wrote the catalogue "
                               "again: it bakes missing and damaged assets anew";
    // Loaded on every core, each with the outcome of one by one (the first bad row reported).
    std::vector<PackingComponent> mixture(entries.size());
    runInParallel(entries.size(), [&](size_t k) {
        const CatalogEntry& e = entries[k];
        const fs::path file = assetFileOf(catalog, e);
        std::error_code ec;
        if (!fs::is_regular_file(file, ec))
            throw Error(catalog, "asset '" + e.name + "': file not found: " + file.string(),
                        rebake + ", or fix its asset column");
        PackingComponent& c = mixture[k];
        c.name = setName + "/" + e.name;
        try {
            // For packing only: without normals, these copies cannot be saved.
            c.asset = loadAsset(file.string(), NodeNormals::Skip);
        } catch (const Error& load) {
            // One fix line: the load's own fix would repeat this one.
            throw Error(catalog, "asset '" + e.name + "': " + load.where() + ": " + load.problem(),
                        rebake);
        }
    }).rethrowIfAny();
    return mixture;
}

} // namespace lsdem
