// [[grain_files]]: grains from a CSV table (a packing from a CT scan, another code or
// lsdem-pack), read by GrainsCsv.h.
#include "SceneSections.h"

#include "lsdem/scene/GrainsCsv.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace lsdem::scenefile {

void readGrainFile(TableReader& t, Scene& scene)
{
    namespace fs = std::filesystem;
    GrainFileSpec f;
    f.where = t.where();
    fs::path file = t.string("file");
    if (file.is_relative()) file = fs::path(scene.directory) / file;
    std::error_code ec;  // a path the system refuses is unreadable, not a filesystem_error
    f.file = fs::absolute(file, ec).lexically_normal().string();
    f.material = lookUpMaterial(t, scene);
    if (t.has("max_overlap")) f.maxOverlap = t.nonNegative("max_overlap", 0.0);
    t.rejectUnknownKeys();

    std::ifstream in(f.file, std::ios::binary);
    if (ec || !in || fs::is_directory(f.file, ec))
        t.fail("file", "cannot read '" + f.file + "'",
               "give a path relative to the scene's folder or an absolute one");
    std::ostringstream text;
    text << in.rdbuf();
    f.first = scene.grains.size();
    readGrainsCsv(text.str(), f.file, f.material, scene);
    f.count = scene.grains.size() - f.first;
    if (f.count == 0)
        t.fail("file", "'" + f.file + "' holds no grains", "add a row per grain below the header");
    scene.grainFiles.push_back(f);
}

} // namespace lsdem::scenefile
