// The rules of a whole scene (SceneValidation.h): the bundled scenes pass; each rule broken
// in a scene built in code is refused with an Error naming the entry, by validateScene, by
// buildWorld and by the writer alike; only a scene file must say when its run ends.
#include "lsdem/scene/SceneValidation.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace lsdem;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

Scene bounce()
{
    return readSceneFile(LSDEM_SOURCE_DIR "/assets/scenes/bounce.toml");
}

struct Breach
{
    std::string what;                   ///< the rule, for the failure message
    std::function<void(Scene&)> apply;  ///< breaks it
    std::string said;                   ///< a part of the Error's text
};

std::vector<Breach> breaches()
{
    return {
        {"material density", [](Scene& s) { s.materials[0].density = -1.0; }, "density must be >= 0"},
        {"contact coefficient", [](Scene& s) { s.contacts[0].model.friction = -0.5; },
         "friction: must be >= 0"},
        {"friction without springs", [](Scene& s) { s.contacts[0].model.friction = 0.5; },
         "has no effect without shear springs"},
        {"contact material index", [](Scene& s) { s.contacts[0].materialB = 7; }, "out of range"},
        {"grain position", [](Scene& s) { s.grains[0].pose.position.x() = kNaN; }, "not finite"},
        {"grain orientation", [](Scene& s) { s.grains[0].pose.orientation = Quat(1, 1, 0, 0); },
         "not a unit quaternion"},
        {"grain asset index", [](Scene& s) { s.grains[0].asset = 3; }, "asset index"},
        {"grain mass", [](Scene& s) { s.grains[0].mass = -2.0; }, "mass must be >= 0"},
        {"boundary material index", [](Scene& s) { s.boundaries[0].material = -1; }, "out of range"},
        {"plane normal", [](Scene& s) { s.boundaries[0].normal = Vec3::Zero(); }, "normal"},
        {"sphere radius",
         [](Scene& s) {
             s.boundaries[0].shape = BoundaryShape::Sphere;
             s.boundaries[0].radius = 0.0;
         },
         "radius must be > 0"},
        {"servo gain",
         [](Scene& s) {
             s.boundaries[0].servo.targetStress = 1.0;
             s.boundaries[0].servo.maxSpeed = 1.0;
             s.boundaries[0].servo.area = 1.0;
             s.boundaries[0].servo.gain = 1.5;
         },
         "servo_gain must be in (0, 1] (got 1.5)"},
        {"global damping", [](Scene& s) { s.globalDamping = 1.0; }, "global_damping must be in [0, 1)"},
        {"gravity", [](Scene& s) { s.gravity.z() = kNaN; }, "gravity must be finite"},
        {"safety", [](Scene& s) { s.timeStep.safety = 2.0; }, "safety must be in (0, 1]"},
        {"end boundary", [](Scene& s) {
             s.end.boundary = 5;
             s.end.displacement = 1.0;
         }, "end_displacement"},
        {"end steps", [](Scene& s) { s.end.steps = -1; }, "end_steps must be >= 0 (got -1)"},
        {"fixed grain moving", [](Scene& s) {
             s.grains[0].motion = GrainMotion::Fixed;
             s.grains[0].angularVelocity = Vec3(0.0, 0.0, 1.0);
         }, "a fixed grain cannot move"},
        {"output period", [](Scene& s) { s.output.vtkPeriod = -1.0; }, "vtk_period must be >= 0"},
        {"history both ways", [](Scene& s) {
             s.output.historyEvery = 10;
             s.output.historyPeriod = 0.1;
         }, "both history_every and history_period"},
        {"names", [](Scene& s) { s.grains.push_back(s.grains[0]); }, "a second grain named"},
    };
}

} // namespace

TEST(SceneValidation, BundledScenesPass)
{
    for (const char* name : {"bounce", "cube27", "sand", "servo", "settle"}) {
        const Scene s = readSceneFile(std::string(LSDEM_SOURCE_DIR "/assets/scenes/") + name + ".toml");
        EXPECT_NO_THROW(validateRunnableScene(s)) << name;
    }
}

TEST(SceneValidation, EachBrokenRuleIsRefusedNamingIt)
{
    const Scene good = bounce();
    ASSERT_NO_THROW(validateRunnableScene(good));
    for (const Breach& b : breaches()) {
        Scene s = good;
        b.apply(s);
        try {
            validateScene(s);
            ADD_FAILURE() << b.what << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(b.said), std::string::npos)
                << b.what << ": " << e.what();
            EXPECT_FALSE(e.where().empty()) << b.what;
        }
    }
}

// buildWorld (a scene built in code: Python, the studies) and the writer hold the same rules,
// before they load an asset or write a byte.
TEST(SceneValidation, BuildWorldAndTheWriterRefuseWhatValidationRefuses)
{
    const Scene good = bounce();
    ASSERT_NO_THROW(sceneToToml(good, "/tmp"));
    const auto refusal = [](const std::function<void()>& f) -> std::string {
        try {
            f();
        } catch (const Error& e) {
            return e.what();
        }
        return "(accepted)";
    };
    for (const Breach& b : breaches()) {
        Scene s = good;
        b.apply(s);
        std::vector<std::string> warnings;
        const std::string built = refusal([&] { buildWorld(s, warnings); });
        const std::string written = refusal([&] { sceneToToml(s, "/tmp"); });
        EXPECT_NE(built.find(b.said), std::string::npos) << b.what << ": " << built;
        EXPECT_NE(written.find(b.said), std::string::npos) << b.what << ": " << written;
    }
}

// A world needs no end condition (a study steps it itself); a scene file does, and the reader
// refuses one without.
TEST(SceneValidation, OnlyARunnableSceneNeedsAnEnd)
{
    Scene s = bounce();
    s.end = EndCondition{};
    EXPECT_NO_THROW(validateScene(s));
    EXPECT_THROW(validateRunnableScene(s), Error);
}
