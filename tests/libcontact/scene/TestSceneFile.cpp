// Scene files: the bundled examples parse to what they say, units and lattices are read right,
// and a table of bad scenes is each refused with a message naming the line, the key and a fix.
#include "lsdem/scene/SceneFile.h"
#include "lsdem/core/Error.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <set>

using namespace lsdem;
using namespace lsdem::test;

namespace {

const std::string kScenes = std::string(LSDEM_SOURCE_DIR) + "/assets/scenes/";

/// A small valid scene; the bad cases below each change one thing in it.
const std::string kGood = R"([units]
length = "mm"
mass = "tonne"
time = "s"
force = "N"

[assets.ball]
shape = "sphere"
radius = 2.0
voxel = 0.25
nodes = 200

[materials.steel]
density = 7.85e-9
[materials.wall]
density = 0.0

[[contacts]]
materials = ["steel", "steel"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.4
restitution = 0.6

[[contacts]]
materials = ["steel", "wall"]
formulation = "original"
testing = "one-way"
normal_stiffness = 1e6

[[grains]]
name = "a"
asset = "ball"
material = "steel"
position = [0, 0, 2]
velocity = [1, 0, 0]
axis_angle = [0, 0, 1, 90]

[[grains]]
asset = "ball"
material = "steel"
position = [5, 0, 2]
mass = 2e-7

[[boundaries]]
name = "floor"
type = "plane"
material = "wall"
point = [0, 0, 0]
normal = [0, 0, 2]

[simulation]
gravity = [0, 0, -9810]
time_step = "auto"
end_time = 0.01

[output]
history_every = 10
vtk_period = 1e-3
)";

/// kGood with the first occurrence of @a from replaced by @a to (which must be found).
std::string edited(const std::string& from, const std::string& to)
{
    std::string s = kGood;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

/// The 1-based line of the first occurrence of @a text in @a scene.
int lineOf(const std::string& scene, const std::string& text)
{
    const size_t at = scene.find(text);
    return 1 + static_cast<int>(std::count(scene.begin(), scene.begin() + static_cast<long>(at), '\n'));
}

} // namespace

TEST(SceneFile, GoodSceneIsReadAsWritten)
{
    const Scene s = parseScene(kGood, "/tmp/x/scene.toml");
    EXPECT_EQ(s.directory, "/tmp/x");
    ASSERT_EQ(s.assets.size(), 1u);
    ASSERT_TRUE(s.assets[0].shape.has_value());
    EXPECT_EQ(s.assets[0].shape->kind, AnalyticShape::Kind::Sphere);
    EXPECT_EQ(s.assets[0].bake.voxelSize, 0.25);
    EXPECT_EQ(s.assets[0].bake.nodePlacement, NodePlacement::Count);
    EXPECT_EQ(s.assets[0].bake.nodeCount, 200);
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "steel");
    EXPECT_EQ(s.materials[0].density, 7.85e-9);
    ASSERT_EQ(s.contacts.size(), 2u);
    EXPECT_EQ(s.contacts[0].model.formulation, Formulation::Adapted);  // the default
    EXPECT_EQ(s.contacts[0].model.damping.restitution(), 0.6);
    EXPECT_EQ(s.contacts[1].model.formulation, Formulation::Original);
    EXPECT_EQ(s.contacts[1].model.testing, NodeTesting::OneWay);
    EXPECT_EQ(s.contacts[1].model.damping.restitution(), 1.0);
    ASSERT_EQ(s.grains.size(), 2u);
    EXPECT_EQ(s.grains[0].name, "a");
    // 90° about z takes x to y.
    EXPECT_NEAR((s.grains[0].pose.orientation * Vec3::UnitX() - Vec3::UnitY()).norm(), 0.0, 1e-15);
    EXPECT_EQ(s.grains[0].velocity, Vec3(1, 0, 0));
    EXPECT_EQ(s.grains[1].mass, 2e-7);
    EXPECT_EQ(s.grains[1].motion, GrainMotion::Free);
    ASSERT_EQ(s.boundaries.size(), 1u);
    EXPECT_EQ(s.boundaries[0].normal, Vec3(0, 0, 1));  // normalised
    EXPECT_EQ(s.gravity, Vec3(0, 0, -9810));
    EXPECT_EQ(s.timeStep.fixed, 0.0);
    EXPECT_EQ(s.end.time, 0.01);
    EXPECT_EQ(s.output.historyEvery, 10);
    EXPECT_EQ(s.output.vtkPeriod, 1e-3);
    EXPECT_EQ(s.grains[0].where, "/tmp/x/scene.toml:" + std::to_string(lineOf(kGood, "[[grains]]")));
}

TEST(SceneFile, BundledExamplesParse)
{
    const Scene bounce = readSceneFile(kScenes + "bounce.toml");
    EXPECT_EQ(bounce.grains.size(), 1u);
    EXPECT_EQ(bounce.end.time, 0.25);

    const Scene cube = readSceneFile(kScenes + "cube27.toml");
    ASSERT_EQ(cube.grains.size(), 27u);
    ASSERT_EQ(cube.boundaries.size(), 6u);
    EXPECT_EQ(cube.boundaries[static_cast<size_t>(cube.end.boundary)].name, "top");
    EXPECT_EQ(cube.end.displacement, 0.3);
    // The stack exactly fills [0, 30]³: centres at 5, 15, 25 along each axis.
    std::set<double> xs;
    for (const GrainSpec& g : cube.grains) {
        xs.insert(g.pose.position.x());
        EXPECT_NEAR(g.pose.orientation.norm(), 1.0, 1e-14);
    }
    EXPECT_EQ(xs, (std::set<double>{5.0, 15.0, 25.0}));

    // The servo lid's area is bounded by the four side walls.
    const Scene servo = readSceneFile(kScenes + "servo.toml");
    ASSERT_EQ(servo.boundaries.size(), 6u);
    const StressServo& lid = servo.boundaries[1].servo;
    EXPECT_EQ(lid.targetStress, 0.6067);
    ASSERT_TRUE(lid.areaFromWalls());
    for (int k = 0; k < 4; ++k)
        EXPECT_EQ(servo.boundaries[size_t(lid.areaWalls[size_t(k)])].name,
                  (std::array<const char*, 4>{"west", "east", "south", "north"})[size_t(k)]);

    const Scene settle = readSceneFile(kScenes + "settle.toml");
    EXPECT_EQ(settle.grains.size(), 36u + 16u);
    ASSERT_FALSE(settle.assets[0].meshFile.empty());
    EXPECT_TRUE(std::filesystem::is_regular_file(settle.assets[0].meshFile));
}

// A servo wall moves at the speed its stress asks, so it can end a run by its displacement.
TEST(SceneFile, ServoWallCanEndARunByDisplacement)
{
    std::string text = readFile(kScenes + "servo.toml");
    const std::string endTime = "end_time = 0.04";
    // Alone it is refused: the wall stops where its stress is met, maybe short of 0.3.
    std::string alone = text;
    alone.replace(alone.find(endTime), endTime.size(),
                  "end_displacement = { boundary = \"top\", value = 0.3 }");
    try {
        parseScene(alone, kScenes + "servo.toml");
        ADD_FAILURE() << "a servo wall's displacement alone was accepted as the end";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("add end_time or end_steps as well"),
                  std::string::npos)
            << e.what();
    }
    text.replace(text.find(endTime), endTime.size(),
                 "end_displacement = { boundary = \"top\", value = 0.3 }\nend_time = 1");
    const Scene scene = parseScene(text, kScenes + "servo.toml");
    ASSERT_GE(scene.end.boundary, 0);
    EXPECT_EQ(scene.boundaries[static_cast<size_t>(scene.end.boundary)].name, "top");
    EXPECT_TRUE(scene.boundaries[static_cast<size_t>(scene.end.boundary)].servo.active());
}

TEST(SceneFile, LatticesAreReproducibleAndJitterStaysWithinBounds)
{
    const std::string lattice = R"(
[[lattices]]
name = "g"
asset = "ball"
material = "steel"
origin = [10, 20, 30]
count = [4, 3, 2]
spacing = [5, 6, 7]
jitter = 0.5
random_orientation = true
seed = 42
)";
    const std::string text = kGood + lattice;
    const Scene a = parseScene(text, "s.toml"), b = parseScene(text, "s.toml");
    ASSERT_EQ(a.grains.size(), 2u + 24u);
    std::set<std::string> names;
    Vec3 meanAxis = Vec3::Zero();
    for (size_t k = 2; k < a.grains.size(); ++k) {
        const GrainSpec& g = a.grains[k];
        EXPECT_EQ(g.pose.position, b.grains[k].pose.position);  // same seed, same lattice
        EXPECT_EQ(g.pose.orientation.coeffs(), b.grains[k].pose.orientation.coeffs());
        names.insert(g.name);
        // Each grain is within the jitter of its lattice site.
        const int i = static_cast<int>(k - 2) % 4, j = static_cast<int>(k - 2) / 4 % 3,
                  l = static_cast<int>(k - 2) / 12;
        const Vec3 site(10 + 5 * i, 20 + 6 * j, 30 + 7 * l);
        EXPECT_LE((g.pose.position - site).cwiseAbs().maxCoeff(), 0.5);
        EXPECT_GT((g.pose.position - site).norm(), 0.0);
        EXPECT_NEAR(g.pose.orientation.norm(), 1.0, 1e-14);
        meanAxis += g.pose.orientation * Vec3::UnitZ();
    }
    EXPECT_EQ(names.size(), 24u);
    EXPECT_TRUE(names.count("g_3_2_1"));
    // Random rotations: the rotated z axes do not all point one way.
    EXPECT_LT(meanAxis.norm() / 24.0, 0.6);
    // Another seed gives another lattice.
    std::string other = text;
    other.replace(other.find("seed = 42"), 9, "seed = 43");
    EXPECT_NE(parseScene(other, "s.toml").grains[2].pose.position, a.grains[2].pose.position);
}

TEST(SceneFile, UnitsMustBeConsistent)
{
    // m, kg, s, N and mm, g, ms, N are both consistent (1 g·mm/ms² = 1 N).
    EXPECT_NO_THROW(parseScene(edited("length = \"mm\"\nmass = \"tonne\"", "length = \"m\"\nmass = \"kg\""), "s.toml"));
    EXPECT_NO_THROW(parseScene(edited("mass = \"tonne\"\ntime = \"s\"", "mass = \"g\"\ntime = \"ms\""), "s.toml"));
    try {
        parseScene(edited("mass = \"tonne\"", "mass = \"kg\""), "s.toml");
        FAIL() << "mm, kg, s, N accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("inconsistent"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("mN"), std::string::npos) << e.what();  // the fix
    }
}

TEST(SceneFile, BadScenesAreRefusedWithLineKeyAndFix)
{
    struct Case
    {
        const char* what;
        std::string text;
        const char* lineOf;   ///< text whose line the message must name
        const char* message;  ///< must appear in the message
    };
    const std::string noEnd = edited("end_time = 0.01\n", "");
    // Grain 0 unnamed (so called grain0), grain 1 named grain0.
    std::string unnamedThenGrain0 = edited("name = \"a\"\n", "");
    unnamedThenGrain0.replace(unnamedThenGrain0.find("position = [5, 0, 2]"), 20,
                              "position = [5, 0, 2]\nname = \"grain0\"");
    // The floor with servo keys added.
    auto servo = [](const std::string& keys) {
        return edited("normal = [0, 0, 2]", "normal = [0, 0, 2]\n" + keys);
    };
    const Case cases[] = {
        {"unknown key", edited("vtk_period", "vtk_every"), "vtk_every", "unknown key 'vtk_every'"},
        {"unknown section", kGood + "[solver]\nx = 1\n", "[solver]", "unknown top-level"},
        {"wrong type", edited("radius = 2.0", "radius = \"2\""), "radius = ", "expected a positive number, got a string"},
        {"negative size", edited("radius = 2.0", "radius = -2.0"), "radius = ", "must be > 0"},
        {"NaN", edited("density = 7.85e-9", "density = nan"), "density = nan", "not finite"},
        {"vector of 2", edited("position = [0, 0, 2]", "position = [0, 0]"), "position = [0, 0]", "array of 3 numbers"},
        {"unknown asset", edited("asset = \"ball\"", "asset = \"bal\""), "asset = \"bal\"", "no asset named 'bal'"},
        {"unknown material", edited("material = \"steel\"", "material = \"stel\""), "material = \"stel\"", "no material named 'stel'"},
        {"missing position", edited("position = [0, 0, 2]\n", ""), "[[grains]]", "missing key 'position'"},
        {"missing contact law", edited("materials = [\"steel\", \"wall\"]", "materials = [\"wall\", \"wall\"]"), "[[boundaries]]", "no contact law between materials 'steel' and 'wall'"},
        {"duplicate contact", edited("materials = [\"steel\", \"wall\"]", "materials = [\"steel\", \"steel\"]"), "[[contacts]]\nmaterials = [\"steel\", \"steel\"]\nformulation", "a second entry"},
        {"unknown formulation", edited("formulation = \"original\"", "formulation = \"hertz\""), "\"hertz\"", "unknown value 'hertz'"},
        {"shear springs with volume", edited("friction = 0.4\n", "formulation = \"volume\"\n"), "shear_stiffness = 5e2", "shear_stiffness: has no effect with formulation volume"},
        {"friction without shear springs", edited("shear_stiffness = 5e2\n", ""), "friction = 0.4", "friction: has no effect without shear springs"},
        {"friction with volume", edited("shear_stiffness = 5e2\n", "formulation = \"volume\"\n"), "friction = 0.4", "friction: has no effect with formulation volume"},
        {"restitution > 1", edited("restitution = 0.6", "restitution = 1.5"), "restitution = 1.5", "(0, 1]"},
        {"no end condition", noEnd, "[simulation]", "no end condition"},
        {"bad time step", edited("time_step = \"auto\"", "time_step = \"fast\""), "\"fast\"", "unknown value 'fast'"},
        {"zero time step", edited("time_step = \"auto\"", "time_step = 0"), "time_step = 0", "must be > 0"},
        {"zero normal", edited("normal = [0, 0, 2]", "normal = [0, 0, 0]"), "normal = [0, 0, 0]", "zero vector"},
        {"inconsistent units", edited("force = \"N\"", "force = \"kN\""), "force = \"kN\"", "inconsistent"},
        {"asset without nodes", edited("nodes = 200\n", ""), "[assets.ball]", "surface nodes"},
        {"node layout of a shape", edited("nodes = 200", "nodes = 200\nnode_layout = \"centroidal\""), "node_layout", "node_layout: applies to meshes"},
        {"two sources", edited("shape = \"sphere\"", "shape = \"sphere\"\nmesh = \"x.obj\""), "[assets.ball]", "more than one source"},
        {"missing mesh file", edited("shape = \"sphere\"\nradius = 2.0", "mesh = \"nowhere.obj\""), "mesh = ", "file not found"},
        {"fixed grain with velocity", edited("velocity = [1, 0, 0]", "velocity = [1, 0, 0]\nmotion = \"fixed\""), "velocity = [1, 0, 0]", "a fixed grain cannot move"},
        {"damping out of range", edited("gravity = [0, 0, -9810]", "gravity = [0, 0, -9810]\nglobal_damping = 1.0"), "global_damping", "[0, 1)"},
        {"end displacement of a fixed wall", edited("end_time = 0.01", "end_displacement = { boundary = \"floor\", value = 1.0 }"), "end_displacement", "does not move"},
        {"bad boundary name", edited("name = \"floor\"", "name = \"floor/1\""), "name = \"floor/1\"", "cannot name a file"},
        {"duplicate grain name", edited("position = [5, 0, 2]", "position = [5, 0, 2]\nname = \"a\""), "[[grains]]\nasset", "a second grain named 'a'"},
        {"a name an unnamed grain gets by default", edited("name = \"a\"", "name = \"grain1\""), "[[grains]]\nasset", "called 'grain1' by default, the name of the grain at /data/scene.toml:"},
        {"the default name of an unnamed grain", unnamedThenGrain0, "[[grains]]\nasset = \"ball\"\nmaterial = \"steel\"\nposition = [5", "a grain named 'grain0', the name the unnamed grain at /data/scene.toml:"},
        {"not TOML", edited("radius = 2.0", "radius = = 2.0"), "radius = = 2.0", "not valid TOML"},
        {"servo stress of the wrong sign", servo("stress = -1.5\narea = 4.0\nmax_speed = 1.0"), "stress = -1.5", "must be > 0"},
        {"servo without area", servo("stress = 1.5\nmax_speed = 1.0"), "stress = 1.5", "needs the area"},
        {"servo with zero area", servo("stress = 1.5\narea = 0.0\nmax_speed = 1.0"), "area = 0.0", "must be > 0"},
        {"servo without limit speed", servo("stress = 1.5\narea = 4.0"), "stress = 1.5", "limit speed"},
        {"servo with zero limit speed", servo("stress = 1.5\narea = 4.0\nmax_speed = 0"), "max_speed = 0", "must be > 0"},
        {"servo with zero gain", servo("stress = 1.5\narea = 4.0\nmax_speed = 1\nservo_gain = 0.0"), "servo_gain", "must be in (0, 1] (got 0)"},
        {"servo with gain above 1", servo("stress = 1.5\narea = 4.0\nmax_speed = 1\nservo_gain = 1.5"), "servo_gain", "(0, 1]"},
        {"servo with a velocity", servo("stress = 1.5\narea = 4.0\nmax_speed = 1\nvelocity = [0, 0, 1]"), "velocity = [0, 0, 1]", "chooses its own velocity"},
        {"servo area and walls", servo("stress = 1.5\narea = 4.0\nmax_speed = 1\narea_walls = [\"a\", \"b\", \"c\", \"d\"]"), "area_walls", "both area and area_walls"},
        {"servo area from unknown walls", servo("stress = 1.5\nmax_speed = 1\narea_walls = [\"a\", \"b\", \"c\", \"d\"]"), "[[boundaries]]", "no boundary named 'a'"},
        {"servo area from three walls", servo("stress = 1.5\nmax_speed = 1\narea_walls = [\"a\", \"b\", \"c\"]"), "area_walls", "four walls"},
        {"area without a servo", servo("area = 4.0"), "area = 4.0", "only makes sense for a servo wall"},
        {"cylinder without radius", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]"), "[[boundaries]]", "missing key 'radius'"},
        {"cylinder of zero radius", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 0"), "radius = 0", "must be > 0"},
        {"cylinder of zero axis", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 5\naxis = [0, 0, 0]"), "axis = [0, 0, 0]", "zero vector"},
        {"cylinder with a plane's key", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 5\nnormal = [0, 0, 1]"), "normal = [0, 0, 1]", "a cylinder boundary takes no 'normal'"},
        {"orifice without thickness", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"orifice\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 2"), "[[boundaries]]", "missing key 'thickness'"},
        {"orifice of negative thickness", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"orifice\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 2\nthickness = -1"), "thickness = -1", "must be > 0"},
        {"orifice of zero radius", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"orifice\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 0\nthickness = 1"), "radius = 0", "must be > 0"},
        {"servo cylinder", edited("type = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 0]\nnormal = [0, 0, 2]", "type = \"cylinder\"\nmaterial = \"wall\"\ncenter = [0, 0, 0]\nradius = 5\nstress = 1.0"), "stress = 1.0", "only a plane can keep a stress"},
        {"non-unit quaternion", edited("axis_angle = [0, 0, 1, 90]", "orientation = [1, 1, 0, 0]"), "orientation", "not a unit quaternion"},
    };
    static_assert(sizeof(cases) / sizeof(cases[0]) >= 20);
    for (const Case& c : cases) {
        try {
            parseScene(c.text, "/data/scene.toml");
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const Error& e) {
            const std::string msg = e.what();
            const int line = lineOf(c.text, c.lineOf);
            EXPECT_NE(msg.find(c.message), std::string::npos) << c.what << ": " << msg;
            EXPECT_EQ(e.where(), "/data/scene.toml:" + std::to_string(line)) << c.what << ": " << msg;
            EXPECT_FALSE(e.fix().empty()) << c.what << ": no fix in: " << msg;
        }
    }
}

// quadrature = "patch" (PatchQuadrature.h) integrates the traction over each node's patch: read
// where the law has a traction per area and a force per node (adapted); refused, at the key's
// line and with a fix, by the laws that have none (original: a spring per node; volume: one
// force per side), and an unknown value refused like any other choice.
TEST(SceneFile, PatchQuadratureIsReadForTheAdaptedLawAndRefusedForOthers)
{
    const Scene nodes = parseScene(kGood, "/data/scene.toml");
    ASSERT_EQ(nodes.contacts.size(), 2u);
    EXPECT_EQ(nodes.contacts[0].model.quadrature, NodeQuadrature::Point);  // the default
    EXPECT_EQ(nodes.contacts[1].model.quadrature, NodeQuadrature::Point);

    const std::string adapted =
        edited("normal_stiffness = 1e3", "quadrature = \"patch\"\nnormal_stiffness = 1e3");
    const Scene patches = parseScene(adapted, "/data/scene.toml");
    EXPECT_EQ(patches.contacts[0].model.formulation, Formulation::Adapted);
    EXPECT_EQ(patches.contacts[0].model.quadrature, NodeQuadrature::Patch);
    EXPECT_EQ(patches.contacts[1].model.quadrature, NodeQuadrature::Point);
    EXPECT_NO_THROW(parseScene(edited("normal_stiffness = 1e3", "quadrature = \"node\"\nnormal_stiffness = 1e3"), "s.toml"));

    const struct
    {
        const char* what;
        std::string text;
        const char* message;
    } refused[] = {
        {"original", edited("testing = \"one-way\"", "testing = \"one-way\"\nquadrature = \"patch\""),
         "not formulation original"},
        {"volume", edited("normal_stiffness = 1e3\nshear_stiffness = 5e2\nfriction = 0.4\n",
                          "formulation = \"volume\"\nquadrature = \"patch\"\nnormal_stiffness = 1e3\n"),
         "not formulation volume"},
        {"unknown value", edited("normal_stiffness = 1e3", "quadrature = \"gauss\"\nnormal_stiffness = 1e3"),
         "unknown value 'gauss'"},
    };
    for (const auto& c : refused) {
        try {
            parseScene(c.text, "/data/scene.toml");
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("quadrature"), std::string::npos) << c.what << ": " << msg;
            EXPECT_NE(msg.find(c.message), std::string::npos) << c.what << ": " << msg;
            EXPECT_EQ(e.where(), "/data/scene.toml:" + std::to_string(lineOf(c.text, "quadrature =")))
                << c.what << ": " << msg;
            EXPECT_NE(e.fix().find("node"), std::string::npos) << c.what << ": " << msg;
        }
    }
}

TEST(SceneFile, MissingFileIsNamed)
{
    try {
        readSceneFile("/nonexistent/scene.toml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "/nonexistent/scene.toml");
    }
}

// Found while writing the scene fuzzer (fuzz/corpus/scene/regression-lattice-*): a lattice of a
// few bytes asked for ten million grains, which took 4 GB and 46 s before anything was checked.
// The whole scene is now held to kMaxSceneGrains (one million), checked before grains are made.
TEST(SceneFile, LatticesCannotAskForMoreGrainsThanTheSceneLimit)
{
    const auto lattice = [](const std::string& count) {
        return "\n[[lattices]]\nasset = \"ball\"\nmaterial = \"steel\"\norigin = [0, 0, 0]\n"
               "count = " + count + "\nspacing = [5, 5, 5]\n";
    };
    // kGood has two grains already: a million more is two too many.
    const std::string text = kGood + lattice("[1000, 1000, 1]");
    try {
        parseScene(text, "/data/scene.toml");
        FAIL() << "a scene of 1000002 grains accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "/data/scene.toml:" + std::to_string(lineOf(text, "count = [1000")));
        EXPECT_NE(e.problem().find("1000002"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("limit of 1000000"), std::string::npos) << e.what();
        EXPECT_FALSE(e.fix().empty());
    }
    // Lattices add up: each alone is fine, together they are not.
    const std::string two = kGood + lattice("[1000, 500, 1]") + lattice("[1000, 500, 1]");
    EXPECT_THROW(parseScene(two, "/data/scene.toml"), Error);
    EXPECT_EQ(parseScene(kGood + lattice("[10, 10, 10]"), "s.toml").grains.size(), 1002u);
}

// Found by review at the same time: the contact-law check kept a table of every pair of
// materials, so a file of 20000 one-line materials asked for 3.2 GB. Laws are now kept by pair.
TEST(SceneFile, ManyMaterialsNeedNoTableOfEveryPair)
{
    std::string text = kGood;
    for (int i = 0; i < 20000; ++i) text += "[materials.m" + std::to_string(i) + "]\n";
    const Scene s = parseScene(text, "s.toml");
    EXPECT_EQ(s.materials.size(), 20002u);
    // A missing law is still found, and named by the first grain that needs it.
    const std::string missing = edited("materials = [\"steel\", \"steel\"]",
                                       "materials = [\"wall\", \"wall\"]");
    try {
        parseScene(missing, "/data/scene.toml");
        FAIL() << "steel grains without a steel-steel law accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "/data/scene.toml:" + std::to_string(lineOf(missing, "[[grains]]")));
        EXPECT_NE(e.problem().find("'steel' and 'steel'"), std::string::npos) << e.what();
    }
}

// Found by fuzzing (fuzz/corpus/scene/regression-file-name-too-long.toml): a mesh path longer
// than the system allows made the existence check throw std::filesystem_error, which named
// neither the scene's line nor the key.
TEST(SceneFile, OverlongAssetPathIsNotFoundWithLineAndKey)
{
    const std::string text =
        edited("shape = \"sphere\"\nradius = 2.0", "mesh = \"" + std::string(5000, 'x') + ".obj\"");
    try {
        parseScene(text, "/data/scene.toml");
        FAIL() << "a 5000-character mesh path accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "/data/scene.toml:" + std::to_string(lineOf(text, "mesh = ")));
        EXPECT_NE(e.problem().find("mesh: file not found"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("File name too long"), std::string::npos) << e.what();
    }
}
