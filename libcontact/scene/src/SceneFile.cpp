// Reading a scene from TOML: the file as a whole (top-level sections, their order, the checks
// across them). Each section has its reader in a file of its own (SceneSections.h), and every
// table goes through a TableReader, so a misspelt key is reported, never ignored.
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/SceneValidation.h"

#include "SceneSections.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem {

namespace {

using namespace scenefile;
namespace fs = std::filesystem;

/// The tables of a [name.*] group (assets, materials) in the order they appear in the file.
std::vector<std::pair<std::string, const toml::table*>> tablesInFileOrder(
    const toml::table* group, const std::string& groupName, const std::string& path)
{
    std::vector<std::pair<std::string, const toml::table*>> out;
    if (!group) return out;
    for (auto&& [key, value] : *group) {
        const std::string name(key.str());
        if (!value.is_table()) {
            TableReader g(*group, "[" + groupName + "]", path);
            throw Error(g.at(value.source()),
                        groupName + "." + name + " must be a table, got " + typeName(value),
                        "write [" + groupName + "." + name + "] and its keys below it");
        }
        out.emplace_back(name, value.as_table());
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return a.second->source().begin.line < b.second->source().begin.line;
    });
    return out;
}

/// The array of tables `[[name]]`, or empty.
std::vector<const toml::table*> arrayOfTables(const toml::table& root, const std::string& name,
                                              const std::string& path)
{
    std::vector<const toml::table*> out;
    const toml::node* n = root.get(name);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) {
        throw Error(path + ":" + std::to_string(n->source().begin.line),
                    "'" + name + "' must be an array of tables",
                    "write each entry as [[" + name + "]] followed by its keys");
    }
    for (const toml::node& e : *a) out.push_back(e.as_table());
    return out;
}

/// The TOML of @a text, whose top-level keys must be a scene's sections, those meant as one
/// table being tables. @throw Error naming the line otherwise.
toml::table parseSceneRoot(const std::string& text, const std::string& path)
{
    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw Error(path + ":" + std::to_string(e.source().begin.line),
                    "not valid TOML: " + std::string(e.description()),
                    "see docs/scenes.md and the examples in assets/scenes/");
    }

    const std::vector<std::string> sections = {"units",      "assets",      "asset_sets",
                                               "materials",  "contacts",    "grains",
                                               "lattices",   "grain_files", "boundaries",
                                               "membranes",  "simulation", "output"};
    for (auto&& [key, value] : root) {
        const std::string k(key.str());
        if (std::find(sections.begin(), sections.end(), k) == sections.end())
            throw Error(path + ":" + std::to_string(value.source().begin.line),
                        "unknown top-level key or table '" + k + "'",
                        "use one of: " + joined(sections));
    }
    for (const char* single :
         {"units", "assets", "asset_sets", "materials", "simulation", "output"}) {
        const toml::node* n = root.get(single);
        if (n && !n->is_table())
            throw Error(path + ":" + std::to_string(n->source().begin.line),
                        "'" + std::string(single) + "' must be a table",
                        "write [" + std::string(single) + "] (or [" + single +
                            ".name]) followed by its keys");
    }

    return root;
}

} // namespace

Scene parseScene(const std::string& text, const std::string& path)
{
    Scene scene;
    scene.path = path;
    scene.directory = fs::absolute(fs::path(path)).parent_path().string();
    scene.text = text;

    const toml::table root = parseSceneRoot(text, path);

    scene.units = readUnits(root["units"].as_table(), path);
    for (const auto& [name, table] : tablesInFileOrder(root["assets"].as_table(), "assets", path))
        scene.assets.push_back(readAsset(name, *table, scene));
    for (const auto& [name, table] :
         tablesInFileOrder(root["asset_sets"].as_table(), "asset_sets", path))
        readAssetSet(name, *table, scene);
    for (const auto& [name, table] :
         tablesInFileOrder(root["materials"].as_table(), "materials", path)) {
        TableReader t(*table, "[materials." + name + "]", path);
        MaterialSpec m;
        m.name = name;
        m.density = t.number("density", 0.0);
        if (std::optional<std::string> p = densityProblem(m.density))
            t.fail("density", *p, kDensityFix);
        t.rejectUnknownKeys();
        scene.materials.push_back(m);
    }
    if (scene.materials.empty())
        throw Error(path, "no materials", "add e.g. [materials.steel] with density = 7.85e-9");

    int n = 0;
    for (const toml::table* t : arrayOfTables(root, "contacts", path)) {
        TableReader r(*t, "[[contacts]] #" + std::to_string(++n), path);
        scene.contacts.push_back(readContact(r, scene));
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "grains", path)) {
        TableReader r(*t, "[[grains]] #" + std::to_string(++n), path);
        if (static_cast<long long>(scene.grains.size()) >= kMaxSceneGrains)
            r.fail("", "is one grain more than the limit of " + std::to_string(kMaxSceneGrains),
                   "split the scene");
        scene.grains.push_back(readGrain(r, scene));
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "lattices", path)) {
        TableReader r(*t, "[[lattices]] #" + std::to_string(++n), path);
        readLattice(r, scene);
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "grain_files", path)) {
        TableReader r(*t, "[[grain_files]] #" + std::to_string(++n), path);
        readGrainFile(r, scene);
    }
    if (scene.grains.empty())
        throw Error(path, "no grains", "add [[grains]], [[lattices]] or [[grain_files]] entries");
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "boundaries", path)) {
        TableReader r(*t, "[[boundaries]] #" + std::to_string(++n), path);
        scene.boundaries.push_back(readBoundary(r, scene));
    }
    n = 0;
    for (const toml::table* t : arrayOfTables(root, "membranes", path)) {
        TableReader r(*t, "[[membranes]] #" + std::to_string(++n), path);
        scene.membranes.push_back(readMembrane(r, scene));
    }
    readSimulation(root["simulation"].as_table(), scene);
    readOutput(root["output"].as_table(), scene);
    checkUniqueNames(scene);  // before the servo walls' area walls are looked up by name
    resolveServoAreaWalls(scene);
    validateRunnableScene(scene);
    return scene;
}

Scene readSceneFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;  // a path the system refuses is unreadable, not a filesystem_error
    if (!in || fs::is_directory(path, ec))
        throw Error(path, "cannot read the scene file", "check the path and its permissions");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path);
}

} // namespace lsdem
