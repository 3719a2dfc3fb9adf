// A grain's keys (GrainKeys.h), written once: each broken rule names its key in the same words
// from a scene file's [[grains]] entry, a [[lattices]] entry and the keys given directly (what
// Python's add_grain does); a grain with every key is written and read back as it was.
#include "lsdem/scene/GrainKeys.h"

#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneValidation.h"
#include "lsdem/scene/SceneWriter.h"

#include <gtest/gtest.h>

using namespace lsdem;

namespace {

struct Case
{
    const char* name;
    GrainKeys keys;         ///< asset 0 ("ball"), material 0 ("steel")
    const char* fileLines;  ///< the same keys after asset and material (position included)
    const char* key;        ///< the key at fault ("" for the entry as a whole)
    const char* words;      ///< "" for good keys
};

template <typename Edit>
GrainKeys keys(Edit edit)
{
    GrainKeys k;
    k.asset = 0;
    k.material = 0;
    k.position = Vec3(0, 0, 5);
    edit(k);
    return k;
}

std::vector<Case> cases()
{
    const Vec3 up = Vec3::UnitZ();
    return {
        {"no position", keys([](GrainKeys& k) { k.position.reset(); }), "", "",
         "missing key 'position'"},
        {"unknown motion", keys([](GrainKeys& k) { k.motion = "rolling"; }),
         "position = [0, 0, 5]\nmotion = \"rolling\"", "motion", "unknown value 'rolling'"},
        {"fixed, moving",
         keys([&](GrainKeys& k) { k.motion = "fixed", k.velocity = up; }),
         "position = [0, 0, 5]\nmotion = \"fixed\"\nvelocity = [0, 0, 1]", "velocity",
         "a fixed grain cannot move"},
        {"fixed, spinning",
         keys([&](GrainKeys& k) { k.motion = "fixed", k.angularVelocity = up; }),
         "position = [0, 0, 5]\nmotion = \"fixed\"\nangular_velocity = [0, 0, 1]",
         "angular_velocity", "a fixed grain cannot move"},
        {"negative mass", keys([](GrainKeys& k) { k.mass = -2.0; }),
         "position = [0, 0, 5]\nmass = -2", "mass", "must be >= 0 (got -2)"},
        {"fixed at rest, its mass from its density",
         keys([&](GrainKeys& k) { k.motion = "fixed", k.velocity = Vec3::Zero(), k.mass = 0.0; }),
         "position = [0, 0, 5]\nmotion = \"fixed\"\nvelocity = [0, 0, 0]\nmass = 0", "", ""},
        {"prescribed, moving",
         keys([&](GrainKeys& k) { k.motion = "prescribed", k.velocity = up; }),
         "position = [0, 0, 5]\nmotion = \"prescribed\"\nvelocity = [0, 0, 1]", "", ""},
    };
}

const char* const kHead =
    "[assets.ball]\nshape = \"sphere\"\nradius = 0.5\nvoxel = 0.05\nnodes = 200\n\n"
    "[materials.steel]\ndensity = 1e-9\n\n[[contacts]]\nmaterials = [\"steel\", \"steel\"]\n"
    "normal_stiffness = 1e3\n\n";

std::string errorOf(const std::string& text)
{
    try {
        parseScene(text, "grains.toml");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(GrainKeys, EachBrokenRuleNamesItsKeyInFileLatticeAndDirectlyAlike)
{
    for (const Case& c : cases()) {
        GrainSpec g;
        g.name = "unchanged";
        const std::optional<KeyProblem> p = applyGrainKeys(c.keys, g);
        const std::string entry = std::string("asset = \"ball\"\nmaterial = \"steel\"\n") + c.fileLines;
        const std::string fromGrain = errorOf(kHead + ("[[grains]]\n" + entry) + "\n\n[simulation]\nend_steps = 1\n");
        if (std::string(c.words).empty()) {
            EXPECT_FALSE(p) << c.name << ": " << p->key << " " << p->problem;
            EXPECT_EQ(fromGrain, "") << c.name;
            continue;
        }
        ASSERT_TRUE(p) << c.name;
        EXPECT_EQ(p->key, c.key) << c.name;
        EXPECT_NE(p->problem.find(c.words), std::string::npos) << c.name << ": " << p->problem;
        EXPECT_EQ(g.name, "unchanged") << c.name << ": a refused grain leaves the spec as it was";
        const std::string said = (p->key.empty() ? "" : p->key + ": ") + p->problem;
        EXPECT_NE(fromGrain.find(said), std::string::npos) << c.name << ": " << fromGrain;
        EXPECT_NE(fromGrain.find(p->fix), std::string::npos) << c.name << ": " << fromGrain;
        if (std::string(c.key) == "" ) continue;  // a lattice has no position, but an origin
        std::string lattice = entry;
        lattice.replace(lattice.find("position"), 8, "origin");
        const std::string fromLattice =
            errorOf(kHead + ("[[lattices]]\ncount = [2, 1, 1]\nspacing = [2, 2, 2]\n" + lattice) +
                    "\n\n[simulation]\nend_steps = 1\n");
        EXPECT_NE(fromLattice.find(said), std::string::npos) << c.name << ": " << fromLattice;
    }
}

TEST(GrainKeys, AGrainWithEveryKeyIsWrittenAndReadBackUnchanged)
{
    const Scene read = parseScene(
        kHead + std::string("[[grains]]\nname = \"spun\"\nasset = \"ball\"\nmaterial = \"steel\"\n"
                            "position = [0.1, 0.2, 0.3]\naxis_angle = [1, 2, 3, 40]\n"
                            "motion = \"prescribed\"\nvelocity = [0, 0, -0.7]\n"
                            "angular_velocity = [3, 0, 0]\nmass = 2.5e-9\n\n"
                            "[[grains]]\nasset = \"ball\"\nmaterial = \"steel\"\n"
                            "position = [4, 0, 0]\nmotion = \"fixed\"\n\n"
                            "[simulation]\nend_steps = 1\n"),
        "every.toml");
    const Scene again = parseScene(sceneToToml(read, "/tmp"), "again.toml");
    ASSERT_EQ(again.grains.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        const GrainSpec& a = read.grains[i];
        const GrainSpec& b = again.grains[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.pose.position, b.pose.position);
        EXPECT_EQ(a.pose.orientation.coeffs(), b.pose.orientation.coeffs());
        EXPECT_EQ(a.motion, b.motion);
        EXPECT_EQ(a.velocity, b.velocity);
        EXPECT_EQ(a.angularVelocity, b.angularVelocity);
        EXPECT_EQ(a.mass, b.mass);
    }
    EXPECT_EQ(read.grains[0].mass, 2.5e-9);
    EXPECT_EQ(read.grains[1].motion, GrainMotion::Fixed);
}

// validateScene applies the same rules to grains built in code, in the file's words.
TEST(GrainKeys, ValidationAppliesTheSchemaToGrainsBuiltInCode)
{
    Scene s = parseScene(kHead + std::string("[[grains]]\nasset = \"ball\"\nmaterial = \"steel\"\n"
                                             "position = [0, 0, 5]\n\n[simulation]\nend_steps = 1\n"),
                         "one.toml");
    s.grains[0].motion = GrainMotion::Fixed;
    s.grains[0].angularVelocity = Vec3(0, 1, 0);
    try {
        validateScene(s);
        ADD_FAILURE() << "a fixed, spinning grain passed";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("the grain's angular_velocity must be zero, as a fixed grain cannot move"),
                  std::string::npos)
            << e.what();
    }
}
