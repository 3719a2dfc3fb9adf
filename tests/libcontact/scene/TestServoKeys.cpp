// The servo wall's rules (ServoKeys.h), written once: each broken rule names its key, leaves the
// wall as it was, and reads the same from a scene file's [[boundaries]] entry as from the keys
// given directly (what Python's add_plane does).
#include "lsdem/scene/ServoKeys.h"

#include "lsdem/scene/SceneFile.h"

#include <gtest/gtest.h>

using namespace lsdem;

namespace {

struct Case
{
    const char* name;
    ServoKeys keys;
    const char* fileLines;  ///< the same keys in a [[boundaries]] entry
    const char* key;        ///< the key at fault ("" when the keys are good)
    const char* words;
};

const std::vector<std::string> kWalls = {"x0", "x1", "y0", "y1"};

std::vector<Case> cases()
{
    return {
        {"good, with an area", {1.5, 4.0, std::nullopt, 2.0, std::nullopt, false},
         "stress = 1.5\narea = 4.0\nmax_speed = 2.0", "", ""},
        {"no stress, an area", {std::nullopt, 4.0, std::nullopt, std::nullopt, std::nullopt, false},
         "area = 4.0", "area", "only makes sense for a servo wall"},
        {"negative stress", {-1.0, 4.0, std::nullopt, 2.0, std::nullopt, false},
         "stress = -1.0\narea = 4.0\nmax_speed = 2.0", "stress", "must be > 0 (got -1)"},
        {"with a velocity", {1.5, 4.0, std::nullopt, 2.0, std::nullopt, true},
         "stress = 1.5\narea = 4.0\nmax_speed = 2.0\nvelocity = [0, 0, 1]", "velocity",
         "chooses its own velocity"},
        {"both areas", {1.5, 4.0, kWalls, 2.0, std::nullopt, false},
         "stress = 1.5\narea = 4.0\nmax_speed = 2.0\narea_walls = [\"x0\", \"x1\", \"y0\", \"y1\"]",
         "area_walls", "both area and area_walls"},
        {"no area", {1.5, std::nullopt, std::nullopt, 2.0, std::nullopt, false},
         "stress = 1.5\nmax_speed = 2.0", "stress", "needs the area"},
        {"three walls", {1.5, std::nullopt, std::vector<std::string>{"x0", "x1", "y0"}, 2.0,
                         std::nullopt, false},
         "stress = 1.5\nmax_speed = 2.0\narea_walls = [\"x0\", \"x1\", \"y0\"]", "area_walls",
         "four walls"},
        {"zero area", {1.5, 0.0, std::nullopt, 2.0, std::nullopt, false},
         "stress = 1.5\narea = 0.0\nmax_speed = 2.0", "area", "must be > 0 (got 0)"},
        {"no limit speed", {1.5, 4.0, std::nullopt, std::nullopt, std::nullopt, false},
         "stress = 1.5\narea = 4.0", "stress", "needs a limit speed"},
        {"zero limit speed", {1.5, 4.0, std::nullopt, 0.0, std::nullopt, false},
         "stress = 1.5\narea = 4.0\nmax_speed = 0.0", "max_speed", "must be > 0 (got 0)"},
        {"gain above 1", {1.5, 4.0, std::nullopt, 2.0, 1.5, false},
         "stress = 1.5\narea = 4.0\nmax_speed = 2.0\nservo_gain = 1.5", "servo_gain",
         "must be in (0, 1] (got 1.5)"},
    };
}

std::string sceneWith(const std::string& lines)
{
    return "[assets.ball]\nshape = \"sphere\"\nradius = 0.5\nvoxel = 0.05\nnodes = 200\n\n"
           "[materials.wall]\ndensity = 1e-9\n\n[[contacts]]\nmaterials = [\"wall\", \"wall\"]\n"
           "normal_stiffness = 1e3\n\n[[grains]]\nasset = \"ball\"\nmaterial = \"wall\"\n"
           "position = [0, 0, 0]\n\n[[boundaries]]\nname = \"top\"\ntype = \"plane\"\n"
           "material = \"wall\"\npoint = [0, 0, 1]\nnormal = [0, 0, -1]\n" +
           lines + "\n\n[simulation]\nend_steps = 1\n";
}

} // namespace

TEST(ServoKeys, EachBrokenRuleNamesItsKeyInFileAndDirectlyAlike)
{
    for (const Case& c : cases()) {
        BoundarySpec wall;
        wall.name = "top";
        const std::optional<KeyProblem> p = applyServoKeys(c.keys, wall);
        std::string fromFile;
        try {
            parseScene(sceneWith(c.fileLines), "servo.toml");
        } catch (const std::exception& e) {
            fromFile = e.what();
        }
        if (std::string(c.key).empty()) {
            EXPECT_FALSE(p) << c.name << ": " << p->key << " " << p->problem;
            EXPECT_EQ(fromFile, "") << c.name;
            EXPECT_EQ(wall.servo.targetStress, 1.5);
            EXPECT_EQ(wall.servo.area, 4.0);
            EXPECT_EQ(wall.servo.maxSpeed, 2.0);
            EXPECT_EQ(wall.servo.gain, 0.5) << "the default gain";
            continue;
        }
        ASSERT_TRUE(p) << c.name;
        EXPECT_EQ(p->key, c.key) << c.name;
        EXPECT_NE(p->problem.find(c.words), std::string::npos) << c.name << ": " << p->problem;
        EXPECT_FALSE(wall.servo.active()) << c.name << ": a refused servo leaves the wall as it was";
        EXPECT_NE(fromFile.find(std::string(c.key) + ": " + p->problem), std::string::npos)
            << c.name << ": " << fromFile;
    }
}
