// Fuzz target for the grains CSV reader ([[grain_files]], GrainsCsv.h): any text must give grains
// or a clear lsdem::Error. What it accepts must write back (grainsCsvText) to text that reads
// to the same grains, bit for bit: the table lsdem-pack writes is the table a scene reads.
#include "FuzzSupport.h"

#include "lsdem/scene/GrainsCsv.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

/// A scene with the assets and materials the corpus's tables name (none of them loaded: the
/// reader looks them up by name only).
lsdem::Scene namesOnly()
{
    lsdem::Scene s;
    for (const char* name : {"ball", "pebble", "grain_01"}) {
        lsdem::AssetSpec a;
        a.name = name;
        s.assets.push_back(a);
    }
    for (const char* name : {"glass", "sand"}) {
        lsdem::MaterialSpec m;
        m.name = name;
        s.materials.push_back(m);
    }
    return s;
}

bool sameGrain(const lsdem::GrainSpec& a, const lsdem::GrainSpec& b)
{
    return a.name == b.name && a.asset == b.asset && a.material == b.material &&
           a.pose.position == b.pose.position &&
           a.pose.orientation.coeffs() == b.pose.orientation.coeffs() &&
           a.velocity == b.velocity && a.angularVelocity == b.angularVelocity;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const lsdem::Scene empty = namesOnly();
    const std::string text(reinterpret_cast<const char*>(data), size);
    lsdem::Scene scene = empty;
    try {
        lsdem::readGrainsCsv(text, "fuzz-input.csv", 0, scene);
    } catch (const lsdem::Error& e) {
        lsdem::fuzz::requireClearError(e);
        return 0;
    }
    const std::string written = lsdem::grainsCsvText(scene, 0, scene.grains.size());
    lsdem::Scene again = empty;
    // The writer leaves the material column out when every grain has the first one's: the
    // scene's [[grain_files]] entry then names it (SceneWriter.cpp), as it does here.
    const int fileMaterial = scene.grains.empty() ? 0 : scene.grains.front().material;
    lsdem::readGrainsCsv(written, "written.csv", fileMaterial, again);  // an Error escapes: a finding
    bool same = again.grains.size() == scene.grains.size();
    for (size_t i = 0; same && i < scene.grains.size(); ++i)
        same = sameGrain(scene.grains[i], again.grains[i]);
    if (!same) {
        std::fprintf(stderr, "lsdem fuzz: grains written as CSV read back differently\n");
        std::abort();
    }
    return 0;
}
