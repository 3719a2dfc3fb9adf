// Fuzz target for the checkpoint reader: any bytes must restore a world or give a clear
// lsdem::Error, as `lsdem-run --restart` reads them: the header (parseCheckpoint), the run's end
// (applyCheckpointEnd) and the world's state (restoreWorldState) into the world of
// fuzz/worlds/checkpoint.toml, built once. The seeds are checkpoints of that world, so mutated
// copies get past the fingerprint to the state, the boundaries and the shear histories.
// A restored world must hold only finite numbers and unit quaternions: a damaged checkpoint
// must not start a run from NaN.
#include "FuzzSupport.h"

#include "lsdem/run/Checkpoint.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

const char kWorldScene[] = LSDEM_SOURCE_DIR "/fuzz/worlds/checkpoint.toml";

struct FuzzWorld
{
    lsdem::Scene scene;
    lsdem::World world;
};

const FuzzWorld& fuzzWorld()
{
    static const FuzzWorld made = [] {
        FuzzWorld w;
        w.scene = lsdem::readSceneFile(kWorldScene);
        std::vector<std::string> warnings;
        w.world = lsdem::buildWorld(w.scene, warnings);
        return w;
    }();
    return made;
}

bool finite(const lsdem::Vec3& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

void requireSaneState(const lsdem::World& w)
{
    bool sane = std::isfinite(w.time) && w.step >= 0;
    for (const lsdem::Grain& g : w.grains) {
        const auto& q = g.body.pose.orientation;
        sane = sane && finite(g.body.pose.position) && finite(g.body.velocity) &&
               finite(g.body.angularMomentum) && finite(g.force) && finite(g.torque) &&
               std::abs(q.norm() - 1.0) < 1e-6;
    }
    for (const lsdem::Boundary& b : w.boundaries)
        sane = sane && finite(b.displacement) && finite(b.force) &&
               std::isfinite(b.normalStiffness) && std::isfinite(b.normalDashpot);
    if (!sane) {
        std::fprintf(stderr, "lsdem fuzz: a checkpoint restored a non-finite or non-unit state\n");
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const FuzzWorld& fixed = fuzzWorld();
    const std::string path = "fuzz-input.lsdem";
    try {
        const lsdem::Checkpoint checkpoint =
            lsdem::parseCheckpoint(std::string(reinterpret_cast<const char*>(data), size), path);
        lsdem::Scene scene = fixed.scene;
        lsdem::applyCheckpointEnd(checkpoint, scene, path);
        lsdem::World world = fixed.world;
        lsdem::restoreWorldState(checkpoint, path, world);
        requireSaneState(world);
    } catch (const lsdem::Error& e) {
        lsdem::fuzz::requireClearError(e);
    }
    return 0;
}
