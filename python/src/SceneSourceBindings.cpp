// Scene builder methods in Python: assets and grains from files, a catalogue's asset set and
// a grains CSV, read as [asset_sets] and [[grain_files]] read them.
#include "SceneBuilding.h"

#include "lsdem/core/Error.h"
#include "lsdem/ls/GrainCatalog.h"
#include "lsdem/scene/GrainsCsv.h"

#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem::python {

namespace fs = std::filesystem;

// Long by nature: one .def per builder method, each with its keyword arguments and docstring.
void bindSceneFileSources(py::class_<Scene>& scene)
{
    scene
        .def("add_asset_set",
             [](Scene& s, const std::string& name, const std::string& catalog) {
                 if (name.empty() || name.find('/') != std::string::npos)
                     throw Error("", "an asset set's name must be non-empty and hold no '/'",
                                 "its assets are named SET/ASSET; e.g. 'sand'");
                 checkNewName(s.assetSets, name, "asset set");
                 AssetSetSpec set;
                 set.name = name;
                 set.catalog = scenePath(s, catalog);
                 set.where = "asset set '" + name + "'";
                 std::error_code ec;
                 if (!fs::is_regular_file(set.catalog, ec))
                     throw Error(set.catalog, "catalogue not found",
                                 "give the catalog.csv lsdem-bake --out-dir wrote (relative "
                                 "paths are from the scene's folder)");
                 const std::vector<CatalogEntry> entries = readCatalog(set.catalog);
                 if (entries.empty())
                     throw Error(set.catalog, "the catalogue lists no assets",
                                 "bake some files into its folder with lsdem-bake --out-dir");
                 const fs::path folder = fs::path(set.catalog).parent_path();
                 std::vector<AssetSpec> added;
                 for (const CatalogEntry& e : entries) {
                     AssetSpec a;
                     a.name = name + "/" + e.name;
                     fs::path file(e.asset);
                     if (file.is_relative()) file = folder / file;
                     a.file = fs::absolute(file).lexically_normal().string();
                     if (!fs::is_regular_file(a.file, ec))
                         throw Error(set.catalog,
                                     "asset '" + e.name + "': file not found: " + a.file,
                                     "bake the set again (lsdem-bake --out-dir), or fix its "
                                     "asset column");
                     checkNewName(s.assets, a.name, "asset");
                     a.set = name;
                     a.where = set.where;
                     added.push_back(std::move(a));
                 }
                 markChanged(s);
                 std::vector<std::string> names;
                 for (AssetSpec& a : added) {
                     names.push_back(a.name);
                     s.assets.push_back(std::move(a));
                 }
                 s.assetSets.push_back(std::move(set));
                 return names;
             },
             py::arg("name"), py::kw_only(), py::arg("catalog"),
             "Every asset of a catalogue (lsdem-bake --out-dir writes DIR/catalog.csv), named "
             "'NAME/ASSET', as [asset_sets.NAME] catalog = ... does; they are loaded when the "
             "scene is simulated. Returns their names. (The TOML reader lists a set's assets "
             "after the [assets] tables: add sets after single assets for to_toml to read back "
             "in the same order.)")
        .def("add_grain_file",
             [](Scene& s, const std::string& file, const std::string& material,
                std::optional<double> maxOverlap) {
                 GrainFileSpec f;
                 f.file = scenePath(s, file);
                 f.material = indexOf(s.materials, material, "material");
                 if (maxOverlap) {
                     if (!(*maxOverlap >= 0.0) || !std::isfinite(*maxOverlap))
                         throw Error("", "max_overlap must be >= 0 (a length)");
                     f.maxOverlap = *maxOverlap;
                 }
                 f.where = "grain file '" + f.file + "'";
                 std::ifstream in(f.file, std::ios::binary);
                 std::error_code ec;
                 if (!in || fs::is_directory(f.file, ec))
                     throw Error(f.file, "cannot read the grains table",
                                 "give a path relative to the scene's folder or an absolute one");
                 std::ostringstream text;
                 text << in.rdbuf();
                 Scene copy = s;  // the scene is unchanged if a row is refused
                 f.first = copy.grains.size();
                 readGrainsCsv(text.str(), f.file, f.material, copy);
                 f.count = copy.grains.size() - f.first;
                 if (f.count == 0)
                     throw Error(f.file, "the table holds no grains",
                                 "add a row per grain below the header");
                 copy.grainFiles.push_back(f);
                 markChanged(copy);
                 s = std::move(copy);
                 return f.count;
             },
             py::arg("file"), py::arg("material"), py::kw_only(),
             py::arg("max_overlap") = py::none(),
             "The grains of a CSV table (lsdem-pack's output, a CT scan, another code: asset, "
             "x, y, z, qw, qx, qy, qz, optional name, material, velocities), as [[grain_files]] "
             "does: assets and materials by name, `material` for rows without one; overlaps "
             "beyond max_overlap (a length; default 5 % of the smaller bounding radius) are "
             "refused when the scene is simulated. Returns the number of grains. (The TOML "
             "reader puts file grains after [[grains]]: add files last for to_toml to read back "
             "in the same order.)");
}

} // namespace lsdem::python
