// [asset_sets.NAME]: many assets at once, from a catalogue or a glob (of baked assets, or of
// meshes baked at load).
#include "SceneSections.h"

#include "lsdem/ls/GrainCatalog.h"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace lsdem::scenefile {

namespace {

namespace fs = std::filesystem;

/// A .vdb file (any case): an asset to load rather than a mesh to bake.
bool isBakedAsset(const fs::path& file)
{
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".vdb";
}

bool hasWildcard(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

/// The regular files in the folder of @a pattern whose names match its last part (fnmatch:
/// *, ?, [...]), sorted by name; the folder part must be a plain path.
std::vector<fs::path> globFiles(const std::string& pattern, TableReader& t)
{
    const fs::path p(pattern);
    const std::string folder = p.parent_path().string(), name = p.filename().string();
    if (hasWildcard(folder))
        t.fail("glob", "has a wildcard in a folder name (" + folder + ")",
               "put wildcards only in the file name, e.g. glob = \"assets/sand/*.vdb\"");
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        t.fail("glob", "the folder " + folder + " does not exist",
               "give a folder relative to the scene's or an absolute one");
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
        std::error_code typeError;
        if (e.is_regular_file(typeError) &&
            ::fnmatch(name.c_str(), e.path().filename().c_str(), FNM_PERIOD) == 0)
            files.push_back(e.path());
    }
    if (ec) t.fail("glob", "cannot list " + folder + " (" + ec.message() + ")", "");
    std::sort(files.begin(), files.end());
    // (A pattern of baked assets ends in .vdb; any other names meshes, baked as the scene
    // is read.)
    const bool namesAssets = p.extension() == ".vdb";
    if (files.empty())
        t.fail("glob", "matches no file (" + pattern + ")",
               namesAssets ? "bake the assets first (lsdem-bake --out-dir), or fix the pattern"
                           : "fix the pattern or the folder: it should match the mesh files");
    return files;
}

} // namespace

void readAssetSet(const std::string& name, const toml::table& table, Scene& scene)
{
    TableReader t(table, "[asset_sets." + name + "]", scene.path);
    AssetSetSpec set;
    set.name = name;
    set.where = t.where();
    if (name.empty() || name.find('/') != std::string::npos)
        t.fail("", "a set's name must be non-empty and hold no '/'",
               "its assets are named SET/ASSET; write e.g. [asset_sets.sand]");
    if (t.has("catalog") == t.has("glob"))
        t.fail("", t.has("glob") ? "has both catalog and glob" : "has neither catalog nor glob",
               "give catalog = \"assets/catalog.csv\" (written by lsdem-bake --out-dir) or "
               "glob = \"assets/sand/*.vdb\"");
    std::vector<std::pair<std::string, std::string>> members;  // asset name, file
    if (t.has("catalog")) {
        set.catalog = resolveScenePath(scene.directory, t.string("catalog"));
        std::error_code notFound;  // a regular file only: a device or a folder is no catalogue
        if (!fs::is_regular_file(set.catalog, notFound))
            t.fail("catalog", "file not found: " + set.catalog,
                   "give a path relative to the scene's folder or an absolute one; "
                   "lsdem-bake --out-dir DIR writes DIR/catalog.csv");
        std::vector<CatalogEntry> entries;
        try {
            entries = readCatalog(set.catalog);
        } catch (const Error& e) {
            // The catalogue's own place (file:line) first; the scene's line after it.
            throw Error(e.where(),
                        e.problem() + " (the catalogue of " + t.label() + " at " +
                            t.where("catalog") + ")",
                        e.fix());
        }
        if (entries.empty())
            t.fail("catalog", "the catalogue " + set.catalog + " lists no assets",
                   "bake some files into its folder with lsdem-bake --out-dir");
        const fs::path folder = fs::path(set.catalog).parent_path();
        for (const CatalogEntry& e : entries) {
            const std::string file = resolveScenePath(folder.string(), e.asset);
            std::error_code ec;
            if (!fs::is_regular_file(file, ec))
                t.fail("catalog",
                       "asset '" + e.name + "' of " + set.catalog + ": file not found: " + file,
                       "bake the set again (lsdem-bake --out-dir), or fix its asset column");
            members.emplace_back(e.name, file);
        }
    } else {
        set.glob = resolveScenePath(scene.directory, t.string("glob"));
        size_t baked = 0;
        for (const fs::path& file : globFiles(set.glob, t)) {
            members.emplace_back(file.stem().string(), file.string());
            baked += isBakedAsset(file);
        }
        if (baked > 0 && baked < members.size())
            t.fail("glob", "matches both baked assets (.vdb) and other files",
                   "narrow the pattern, e.g. \"*.vdb\" or \"*.stl\"");
        set.meshes = baked == 0;
    }
    if (set.meshes) {
        readBakeKeys(t, set.bake, false, "scene " + scene.path + " asset set " + name);
    } else {
        for (const char* key :
             {"voxel", "node_spacing", "nodes", "mesh_nodes", "areas", "node_layout"})
            if (t.has(key))
                t.fail(key, "has no effect on baked assets",
                       "remove it, or use glob = \"meshes/*.stl\" to bake meshes at load");
    }
    t.rejectUnknownKeys();

    for (const auto& [member, file] : members) {
        AssetSpec a;
        a.name = name + "/" + member;
        (set.meshes ? a.meshFile : a.file) = file;
        a.bake = set.bake;
        a.set = name;
        a.where = set.where;
        if (indexByName(scene.assets, a.name) >= 0)
            t.fail("", "a second asset named '" + a.name + "'",
                   "rename the [assets] table or the set");
        scene.assets.push_back(std::move(a));
    }
    scene.assetSets.push_back(std::move(set));
}

} // namespace lsdem::scenefile
