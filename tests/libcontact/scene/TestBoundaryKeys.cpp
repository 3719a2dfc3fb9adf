// The [[boundaries]] schema (BoundaryKeys.h), written once: each broken rule names its key in the
// same words from a scene file's entry and from the keys given directly (what Python's add_*
// methods do); every type is written and read back as it was; docs/scenes.md's table of types
// lists exactly the schema's keys.
#include "lsdem/scene/BoundaryKeys.h"

#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneValidation.h"
#include "lsdem/scene/SceneWriter.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

using namespace lsdem;

namespace {

struct Case
{
    const char* name;
    BoundaryKeys keys;      ///< material 0 ("wall") and asset 0 ("ball") by index
    const char* fileLines;  ///< the same keys in a [[boundaries]] entry after name and material
    const char* key;        ///< the key at fault ("" for the entry as a whole)
    const char* words;
};

BoundaryKeys keys(const char* type)
{
    BoundaryKeys k;
    k.name = "b";
    k.type = type;
    k.material = 0;
    return k;
}

template <typename Edit>
BoundaryKeys keys(const char* type, Edit edit)
{
    BoundaryKeys k = keys(type);
    edit(k);
    return k;
}

std::vector<Case> cases()
{
    const Vec3 z = Vec3::UnitZ(), o = Vec3::Zero();
    return {
        {"no type", keys(""), "", "", "missing key 'type'"},
        {"unknown type", keys("cone"), "type = \"cone\"", "type", "unknown value 'cone'"},
        {"plane without normal", keys("plane", [&](BoundaryKeys& k) { k.point = o; }),
         "type = \"plane\"\npoint = [0, 0, 0]", "", "missing key 'normal'"},
        {"plane of zero normal",
         keys("plane", [&](BoundaryKeys& k) { k.point = o, k.normal = o; }),
         "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 0]", "normal", "zero vector"},
        {"plane with one width",
         keys("plane", [&](BoundaryKeys& k) { k.point = o, k.normal = z, k.extent = {{2.0, 0.0}}; }),
         "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nextent = [2, 0]", "extent",
         "both widths must be > 0"},
        {"patch axis without a patch",
         keys("plane", [&](BoundaryKeys& k) { k.point = o, k.normal = z, k.axisU = Vec3::UnitX(); }),
         "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\naxis_u = [1, 0, 0]", "axis_u",
         "only makes sense with extent"},
        {"patch axis along the normal",
         keys("plane",
              [&](BoundaryKeys& k) { k.point = o, k.normal = z, k.extent = {{1.0, 1.0}}, k.axisU = z; }),
         "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nextent = [1, 1]\naxis_u = [0, 0, 3]",
         "axis_u", "parallel to the normal"},
        {"plane of negative depth",
         keys("plane", [&](BoundaryKeys& k) { k.point = o, k.normal = z, k.thickness = -1.0; }),
         "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nthickness = -1", "thickness",
         "must be > 0 (got -1)"},
        {"sphere with a plane's key",
         keys("sphere", [&](BoundaryKeys& k) { k.center = o, k.radius = 1.0, k.normal = z; }),
         "type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nnormal = [0, 0, 1]", "normal",
         "a sphere boundary takes no 'normal'"},
        {"sphere of zero radius",
         keys("sphere", [&](BoundaryKeys& k) { k.center = o, k.radius = 0.0; }),
         "type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0", "radius", "must be > 0 (got 0)"},
        {"cylinder with a stress",
         keys("cylinder", [&](BoundaryKeys& k) { k.center = o, k.radius = 1.0, k.servo.stress = 1.0; }),
         "type = \"cylinder\"\ncenter = [0, 0, 0]\nradius = 1\nstress = 1", "stress",
         "only a plane can keep a stress"},
        {"orifice without thickness",
         keys("orifice", [&](BoundaryKeys& k) { k.center = o, k.radius = 1.0; }),
         "type = \"orifice\"\ncenter = [0, 0, 0]\nradius = 1", "", "missing key 'thickness'"},
        {"orifice of zero axis",
         keys("orifice",
              [&](BoundaryKeys& k) { k.center = o, k.radius = 1.0, k.thickness = 0.5, k.axis = o; }),
         "type = \"orifice\"\ncenter = [0, 0, 0]\nradius = 1\nthickness = 0.5\naxis = [0, 0, 0]",
         "axis", "zero vector"},
        {"level set without position", keys("level-set", [&](BoundaryKeys& k) { k.asset = 0; }),
         "type = \"level-set\"\nasset = \"ball\"", "", "missing key 'position'"},
        {"level set with a radius",
         keys("level-set", [&](BoundaryKeys& k) { k.asset = 0, k.position = o, k.radius = 2.0; }),
         "type = \"level-set\"\nasset = \"ball\"\nposition = [0, 0, 0]\nradius = 2", "radius",
         "a level-set boundary takes no 'radius'"},
        {"good orifice",
         keys("orifice",
              [&](BoundaryKeys& k) { k.center = o, k.radius = 1.0, k.thickness = 0.5; }),
         "type = \"orifice\"\ncenter = [0, 0, 0]\nradius = 1\nthickness = 0.5", "", ""},
    };
}

/// A scene with one grain and the [[boundaries]] entries @a boundaries (their tables' keys, the
/// first entry's header given).
std::string sceneWithBoundaries(const std::string& boundaries)
{
    return "[assets.ball]\nshape = \"sphere\"\nradius = 0.5\nvoxel = 0.05\nnodes = 200\n\n"
           "[materials.wall]\ndensity = 1e-9\n\n[[contacts]]\nmaterials = [\"wall\", \"wall\"]\n"
           "normal_stiffness = 1e3\n\n[[grains]]\nasset = \"ball\"\nmaterial = \"wall\"\n"
           "position = [0, 0, 5]\n\n[[boundaries]]\n" +
           boundaries + "\n\n[simulation]\nend_steps = 1\n";
}

std::string sceneWith(const std::string& name, const std::string& lines)
{
    return sceneWithBoundaries("name = \"" + name + "\"\nmaterial = \"wall\"\n" + lines);
}

std::string errorOf(const std::string& text)
{
    try {
        parseScene(text, "boundary.toml");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(BoundaryKeys, EachBrokenRuleNamesItsKeyInFileAndDirectlyAlike)
{
    for (const Case& c : cases()) {
        BoundarySpec b;
        b.name = "unchanged";
        const std::optional<KeyProblem> p = applyBoundaryKeys(c.keys, b);
        const std::string fromFile = errorOf(sceneWith("b", c.fileLines));
        if (std::string(c.words).empty()) {
            EXPECT_FALSE(p) << c.name << ": " << p->key << " " << p->problem;
            EXPECT_EQ(fromFile, "") << c.name;
            EXPECT_EQ(b.name, "b");
            continue;
        }
        ASSERT_TRUE(p) << c.name;
        EXPECT_EQ(p->key, c.key) << c.name;
        EXPECT_NE(p->problem.find(c.words), std::string::npos) << c.name << ": " << p->problem;
        EXPECT_EQ(b.name, "unchanged") << c.name << ": a refused entry leaves the boundary as it was";
        const std::string said = (p->key.empty() ? "" : p->key + ": ") + p->problem;
        EXPECT_NE(fromFile.find(said), std::string::npos) << c.name << ": " << fromFile;
        EXPECT_NE(fromFile.find(p->fix), std::string::npos) << c.name << ": " << fromFile;
    }
}

TEST(BoundaryKeys, ANameThatCannotNameAFileIsRefused)
{
    BoundaryKeys k = keys("sphere");
    k.center = Vec3::Zero();
    k.radius = 1.0;
    for (const char* name : {"", "a/b", "top wall"}) {
        k.name = name;
        BoundarySpec b;
        const std::optional<KeyProblem> p = applyBoundaryKeys(k, b);
        ASSERT_TRUE(p) << name;
        EXPECT_EQ(p->key, "name");
        EXPECT_NE(p->problem.find("cannot name a file"), std::string::npos);
    }
}

TEST(BoundaryKeys, DirectionsAreMadeUnitAndAPatchAxisTurnedIntoThePlane)
{
    BoundaryKeys k = keys("plane");
    k.point = Vec3(1, 2, 3);
    k.normal = Vec3(0, 0, 2);
    k.extent = {{4.0, 2.0}};
    k.axisU = Vec3(3, 0, 4);  // tilted out of the plane: its in-plane part is x
    BoundarySpec b;
    ASSERT_FALSE(applyBoundaryKeys(k, b));
    EXPECT_EQ(b.normal, Vec3::UnitZ());
    EXPECT_NEAR((b.axisU - Vec3::UnitX()).norm(), 0.0, 1e-15);
    EXPECT_EQ(b.extentU, 4.0);
    EXPECT_EQ(b.extentV, 2.0);
    EXPECT_EQ(b.point, Vec3(1, 2, 3));
}

// Each type, with every key it may have, written by the scene writer and read back: the same
// boundary, bit for bit; and boundaryKeysOf gives back what built it.
TEST(BoundaryKeys, EveryTypeIsWrittenAndReadBackUnchanged)
{
    const std::string entries =
        "name = \"floor\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\n"
        "normal = [0, 0, 1]\nextent = [3, 2]\naxis_u = [0.6, 0.8, 0]\nthickness = 0.25\n\n"
        "[[boundaries]]\nname = \"x0\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [-2, 0, 0]\n"
        "normal = [1, 0, 0]\n\n"
        "[[boundaries]]\nname = \"x1\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [2, 0, 0]\n"
        "normal = [-1, 0, 0]\n\n"
        "[[boundaries]]\nname = \"y0\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, -2, 0]\n"
        "normal = [0, 1, 0]\n\n"
        "[[boundaries]]\nname = \"y1\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, 2, 0]\n"
        "normal = [0, -1, 0]\n\n"
        "[[boundaries]]\nname = \"lid\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 9]\n"
        "normal = [0, 0, -1]\nstress = 0.5\narea_walls = [\"x0\", \"x1\", \"y0\", \"y1\"]\n"
        "max_speed = 2\nservo_gain = 0.25\n\n"
        "[[boundaries]]\nname = \"ball\"\ntype = \"sphere\"\nmaterial = \"wall\"\n"
        "center = [0, 0, 20]\nradius = 1.5\nvelocity = [0, 0, -0.1]\n\n"
        "[[boundaries]]\nname = \"drum\"\ntype = \"cylinder\"\nmaterial = \"wall\"\n"
        "center = [0, 0, 0]\nradius = 7\naxis = [0, 1, 1]\n\n"
        "[[boundaries]]\nname = \"hole\"\ntype = \"orifice\"\nmaterial = \"wall\"\n"
        "center = [0, 0, -1]\nradius = 1\nthickness = 0.5\n\n"
        "[[boundaries]]\nname = \"rock\"\ntype = \"level-set\"\nasset = \"ball\"\n"
        "material = \"wall\"\nposition = [5, 5, 5]\naxis_angle = [0, 0, 1, 30]";
    const Scene read = parseScene(sceneWithBoundaries(entries), "every.toml");
    ASSERT_EQ(read.boundaries.size(), 10u);
    const Scene again = parseScene(sceneToToml(read, "/tmp"), "again.toml");
    ASSERT_EQ(again.boundaries.size(), read.boundaries.size());
    for (size_t i = 0; i < read.boundaries.size(); ++i) {
        const BoundarySpec& a = read.boundaries[i];
        const BoundarySpec& b = again.boundaries[i];
        SCOPED_TRACE(a.name);
        EXPECT_EQ(a.shape, b.shape);
        EXPECT_EQ(a.point, b.point);
        EXPECT_EQ(a.normal, b.normal);
        EXPECT_EQ(a.extentU, b.extentU);
        EXPECT_EQ(a.extentV, b.extentV);
        EXPECT_EQ(a.axisU, b.axisU);
        EXPECT_EQ(a.thickness, b.thickness);
        EXPECT_EQ(a.center, b.center);
        EXPECT_EQ(a.radius, b.radius);
        EXPECT_EQ(a.axis, b.axis);
        EXPECT_EQ(a.asset, b.asset);
        EXPECT_EQ(a.pose.position, b.pose.position);
        EXPECT_EQ(a.pose.orientation.coeffs(), b.pose.orientation.coeffs());
        EXPECT_EQ(a.velocity, b.velocity);
        EXPECT_EQ(a.servo.targetStress, b.servo.targetStress);
        EXPECT_EQ(a.servo.areaWalls, b.servo.areaWalls);
        EXPECT_EQ(a.servo.maxSpeed, b.servo.maxSpeed);
        EXPECT_EQ(a.servo.gain, b.servo.gain);
        // The keys of a boundary build it again.
        BoundarySpec rebuilt;
        ASSERT_FALSE(applyBoundaryKeys(boundaryKeysOf(a, read), rebuilt));
        EXPECT_EQ(rebuilt.axisU, a.axisU);
        EXPECT_EQ(rebuilt.thickness, a.thickness);
    }
    EXPECT_EQ(read.boundaries[0].axisU, Vec3(0.6, 0.8, 0.0).normalized());
    EXPECT_TRUE(read.boundaries[5].servo.areaFromWalls());
}

// validateScene applies the same rules to a Scene built in code, in the file's words.
TEST(BoundaryKeys, ValidationAppliesTheSchemaToBoundariesBuiltInCode)
{
    Scene s = parseScene(sceneWith("top", "type = \"plane\"\npoint = [0, 0, 9]\nnormal = [0, 0, -1]"),
                         "top.toml");
    s.boundaries[0].extentU = 2.0;  // and extentV left 0
    try {
        validateScene(s);
        ADD_FAILURE() << "a patch with one width passed";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("boundary 'top': extent both widths must be > 0"),
                  std::string::npos)
            << e.what();
    }
    s.boundaries[0].extentU = 0.0;
    s.boundaries[0].thickness = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(validateScene(s), std::exception);
}

// docs/scenes.md's table of boundary types: a row per type of the schema, naming each key that
// type needs or may have, and no type the schema lacks.
TEST(BoundaryKeys, ScenesMdListsEachTypeWithItsKeys)
{
    std::ifstream in(LSDEM_SOURCE_DIR "/docs/scenes.md");
    ASSERT_TRUE(in) << "docs/scenes.md not found";
    std::vector<std::string> rows;
    bool inTable = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| `type` |", 0) == 0) inTable = true;
        else if (inTable && line.rfind("| `", 0) == 0) rows.push_back(line);
        else if (inTable && line.rfind("|---", 0) != 0) break;
    }
    ASSERT_EQ(rows.size(), boundaryTypes().size()) << "one row per boundary type";
    for (const BoundaryType& t : boundaryTypes()) {
        const auto row = std::find_if(rows.begin(), rows.end(), [&](const std::string& r) {
            return r.rfind("| `" + t.name + "` |", 0) == 0;
        });
        ASSERT_NE(row, rows.end()) << "no row for " << t.name;
        std::vector<std::string> keys = t.required;
        keys.insert(keys.end(), t.optional.begin(), t.optional.end());
        for (const std::string& key : keys)
            EXPECT_NE(row->find("`" + key + "`"), std::string::npos)
                << "the " << t.name << " row does not name `" << key << "`";
        EXPECT_NE(row->find(t.grainsLive), std::string::npos) << t.name;
    }
}
