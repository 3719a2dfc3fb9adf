// [[membranes]] in scene files: a tube is read as given, built stretched round with its rims
// held by the nearest named planes, written back the same, and every bad entry is refused
// naming its line, key and fix.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/MembraneStateCsv.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace lsdem;

namespace {

/// Two balls between a floor and a lid, in a latex tube sealed to both.
const std::string kTube = R"([assets.ball]
shape = "sphere"
radius = 1.0
voxel = 0.25
nodes = 100

[materials.steel]
density = 7.85e-9
[materials.wall]
density = 0.0
[materials.latex]
density = 0.0

[[contacts]]
materials = ["steel", "steel"]
normal_stiffness = 1e3
[[contacts]]
materials = ["steel", "wall"]
normal_stiffness = 1e3
[[contacts]]
materials = ["steel", "latex"]
normal_stiffness = 1e3

[[grains]]
asset = "ball"
material = "steel"
position = [0, 0, 3]
[[grains]]
asset = "ball"
material = "steel"
position = [0, 0, 6]

[[boundaries]]
name = "floor"
type = "plane"
material = "wall"
point = [0, 0, 0]
normal = [0, 0, 1]
[[boundaries]]
name = "lid"
type = "plane"
material = "wall"
point = [0, 0, 10]
normal = [0, 0, -1]

[[membranes]]
name = "sleeve"
material = "latex"
shape = "tube"
youngs = 1.4
poisson = 0.45
thickness = 0.3
density = 1e-6
pressure = 0.1
drag = 0.02
base = [0, 0, 0]
axis = [0, 0, 1]
radius = 1.5
height = 10
segments = 24
rings = 8
prestretch = 1.05
hold = ["lid", "floor"]

[simulation]
time_step = "auto"
end_steps = 10
)";

std::string edited(const std::string& from, const std::string& to)
{
    std::string s = kTube;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

std::string refusal(const std::string& text)
{
    try {
        parseScene(text, "membrane.toml");
    } catch (const Error& e) {
        return e.what();
    }
    return "accepted";
}

} // namespace

TEST(SceneMembranes, ATubeIsBuiltStretchedRoundAndHeldByTheNearestPlanes)
{
    const Scene scene = parseScene(kTube, "membrane.toml");
    ASSERT_EQ(scene.membranes.size(), 1u);
    const MembraneSpec& spec = scene.membranes[0];
    EXPECT_EQ(spec.name, "sleeve");
    EXPECT_EQ(spec.material, 2);
    EXPECT_EQ(spec.rubber.youngs, 1.4);
    EXPECT_EQ(spec.pressure, 0.1);
    EXPECT_EQ(spec.hold, (std::vector<int>{1, 0}));

    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    ASSERT_EQ(w.membranes.size(), 1u);
    const Membrane& m = w.membranes[0];
    ASSERT_EQ(m.positions.size(), 24u * 9u);
    EXPECT_EQ(m.material, 2);
    EXPECT_EQ(m.pressure, 0.1);
    EXPECT_EQ(m.drag, 0.02);
    EXPECT_EQ(m.rimCount, 2);
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const Vec3& x = m.positions[v];
        EXPECT_NEAR(std::hypot(x.x(), x.y()), 1.5, 1e-12) << v;  // placed at the radius given
        const int ring = int(v / 24);
        EXPECT_EQ(m.heldBy[v], ring == 0 ? 0 : ring == 8 ? 1 : -1) << v;  // floor, lid, free
    }
    // Its rubber is unstretched at radius/prestretch: the reference areas are those of that
    // tube's facets, 2N·r·sin(π/N)·H.
    double area = 0.0;
    for (const MembraneTriangle& t : m.triangles) area += t.area;
    EXPECT_NEAR(area, 2.0 * 24 * (1.5 / 1.05) * std::sin(kPi / 24) * 10.0, 1e-9);
}

TEST(SceneMembranes, AreWrittenAndReadBackTheSame)
{
    const Scene scene = parseScene(kTube, "membrane.toml");
    const Scene again = parseScene(sceneToToml(scene, "."), "written.toml");
    ASSERT_EQ(again.membranes.size(), 1u);
    const MembraneSpec &a = scene.membranes[0], &b = again.membranes[0];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.material, b.material);
    EXPECT_EQ(a.rubber.youngs, b.rubber.youngs);
    EXPECT_EQ(a.rubber.poisson, b.rubber.poisson);
    EXPECT_EQ(a.rubber.thickness, b.rubber.thickness);
    EXPECT_EQ(a.rubber.density, b.rubber.density);
    EXPECT_EQ(a.pressure, b.pressure);
    EXPECT_EQ(a.drag, b.drag);
    EXPECT_EQ(a.base, b.base);
    EXPECT_EQ(a.axis, b.axis);
    EXPECT_EQ(a.radius, b.radius);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.segments, b.segments);
    EXPECT_EQ(a.rings, b.rings);
    EXPECT_EQ(a.prestretch, b.prestretch);
    EXPECT_EQ(a.hold, b.hold);
}

TEST(SceneMembranes, BadEntriesAreRefusedWithLineKeyAndFix)
{
    struct Case
    {
        std::string text;
        const char* message;
    };
    const Case cases[] = {
        {edited("shape = \"tube\"", "shape = \"sphere\""), "membrane.toml:49: [[membranes]] #1 shape: unknown membrane shape 'sphere'"},
        {edited("poisson = 0.45", "poisson = 0.5"), "membrane.toml:51: [[membranes]] #1 poisson: must be in [0, 0.5) (got 0.5)"},
        {edited("thickness = 0.3", "thickness = 0"), "[[membranes]] #1 thickness: must be > 0 (got 0)"},
        {edited("density = 1e-6", "density = nan"), "density: is not finite"},
        {edited("segments = 24", "segments = 2"), "segments: must be at least 3 (got 2)"},
        {edited("segments = 24", "segments = 100000000"), "segments: must be at most 1e7 (got 100000000)"},
        {edited("segments = 24", "segments = 2000000"), "segments: and rings make 1.8e+07 vertices, over the limit of 1e7"},
        {edited("prestretch = 1.05", "prestretch = 0.9"), "prestretch: must be at least 1 (got 0.9)"},
        {edited("drag = 0.02", "drags = 0.02"), "unknown key 'drags'"},
        {edited("hold = [\"lid\", \"floor\"]", "hold = [\"lid\", \"flor\"]"), "hold: no boundary named 'flor'"},
        {edited("hold = [\"lid\", \"floor\"]", "hold = \"lid\""), "hold: expected the names of the plane boundaries"},
        {edited("hold = [\"lid\", \"floor\"]", "hold = [\"lid\"]") , "accepted"},
        {edited("materials = [\"steel\", \"latex\"]", "materials = [\"wall\", \"latex\"]"), "no contact law between materials 'steel' and 'latex'"},
        {kTube + "[[membranes]]\nname = \"sleeve\"\nmaterial = \"latex\"\nshape = \"tube\"\nyoungs = 1\n"
                 "poisson = 0.4\nthickness = 1\ndensity = 1\nbase = [0, 0, 0]\nradius = 1\n"
                 "height = 1\nsegments = 3\nrings = 1\n",
         "a second membrane named 'sleeve'"},
    };
    for (const Case& c : cases)
        EXPECT_NE(refusal(c.text).find(c.message), std::string::npos)
            << "expected: " << c.message << "\ngot: " << refusal(c.text);
}

TEST(SceneMembranes, ARimHeldByANonPlaneOrByNothingNearIsRefusedWhenBuilt)
{
    // Both rims nearest the floor: the lid holds none.
    Scene scene = parseScene(kTube, "membrane.toml");
    scene.boundaries[1].point = Vec3(0, 0, -5);
    std::vector<std::string> warnings;
    try {
        buildWorld(scene, warnings);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'lid' is the nearest boundary to none of its rims"),
                  std::string::npos)
            << e.what();
    }
    const std::string sphere = edited(
        "name = \"lid\"\ntype = \"plane\"\nmaterial = \"wall\"\npoint = [0, 0, 10]\nnormal = [0, 0, -1]",
        "name = \"lid\"\ntype = \"sphere\"\nmaterial = \"wall\"\ncenter = [0, 0, 20]\nradius = 5");
    const Scene withSphere = parseScene(sphere, "membrane.toml");
    try {
        buildWorld(withSphere, warnings);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'lid' is not a plane"), std::string::npos) << e.what();
    }
}

namespace {

/// A scratch folder for a test's files, removed with it.
struct ScratchFolder
{
    std::filesystem::path path;
    explicit ScratchFolder(const std::string& name)
        : path(std::filesystem::temp_directory_path() / ("lsdem_" + name + "_" + std::to_string(::getpid())))
    {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~ScratchFolder() { std::filesystem::remove_all(path); }
    std::string write(const std::string& file, const std::string& text) const
    {
        std::ofstream((path / file).string(), std::ios::binary) << text;
        return (path / file).string();
    }
};

} // namespace

// A run's membrane as it left it: `state` places the tube's vertices (and their velocities)
// where the file says, with its rubber's unstretched shape still the tube's keys'; written and
// read back to the same bits, and the scene round-trips with the key. Fails if the state were
// ignored, or the reference shapes made from the state instead of the tube.
TEST(SceneMembranes, AStateFilePlacesTheVerticesWhereARunLeftThem)
{
    const ScratchFolder folder("membrane_state");
    std::vector<std::string> warnings;
    World w = buildWorld(parseScene(kTube, "membrane.toml"), warnings);
    Membrane moved = w.membranes[0];
    for (size_t v = 0; v < moved.positions.size(); ++v) {
        const Vec3& x = moved.positions[v];
        // swollen by a tenth round its middle, drifting up
        const double bulge = 1.0 + 0.1 * std::sin(kPi * x.z() / 10.0);
        moved.positions[v] = Vec3(bulge * x.x(), bulge * x.y(), x.z() + 1e-3 * double(v % 7) / 3.0);
        moved.velocities[v] = Vec3(0.1 / 3.0, -double(v), 1e-17 * double(v));
    }
    writeMembraneStateCsv(moved, (folder.path / "sleeve_state.csv").string());
    const std::string sceneFile =
        folder.write("scene.toml", edited("hold = [\"lid\", \"floor\"]",
                                          "hold = [\"lid\", \"floor\"]\nstate = \"sleeve_state.csv\""));
    const Scene scene = readSceneFile(sceneFile);
    ASSERT_EQ(scene.membranes[0].state, (folder.path / "sleeve_state.csv").string());
    const World placed = buildWorld(scene, warnings);
    const Membrane& m = placed.membranes[0];
    EXPECT_EQ(m.positions, moved.positions);    // bit for bit (17 digits)
    EXPECT_EQ(m.velocities, moved.velocities);
    ASSERT_EQ(m.triangles.size(), w.membranes[0].triangles.size());
    for (size_t t = 0; t < m.triangles.size(); ++t) {  // the tube's rubber, not the state's
        EXPECT_EQ(m.triangles[t].area, w.membranes[0].triangles[t].area) << t;
        EXPECT_EQ(m.triangles[t].inverseShape, w.membranes[0].triangles[t].inverseShape) << t;
    }
    EXPECT_EQ(m.heldBy, w.membranes[0].heldBy);
    EXPECT_EQ(m.masses, w.membranes[0].masses);
    // Written back, the scene names the same file (relative to its folder, as read).
    const std::string text = sceneToToml(scene, folder.path.string());
    EXPECT_NE(text.find("state = 'sleeve_state.csv'"), std::string::npos) << text;
    const Scene again = parseScene(text, sceneFile);
    EXPECT_EQ(again.membranes[0].state, scene.membranes[0].state);
}

// A state file that is missing, has a wrong header, a row too few, a word or a NaN for a
// number is refused when the world is built, naming the file (and the line) and the fix.
TEST(SceneMembranes, ABadStateFileIsRefusedNamingTheFileAndLine)
{
    const ScratchFolder folder("membrane_bad_state");
    std::vector<std::string> warnings;
    const World w = buildWorld(parseScene(kTube, "membrane.toml"), warnings);
    const std::string good = membraneStateCsvText(w.membranes[0]);
    const auto refusedWith = [&](const std::string& csv) -> std::string {
        if (!csv.empty()) folder.write("state.csv", csv);
        else std::filesystem::remove(folder.path / "state.csv");
        const std::string sceneFile = folder.write(
            "scene.toml", edited("hold = [\"lid\", \"floor\"]",
                                 "hold = [\"lid\", \"floor\"]\nstate = \"state.csv\""));
        try {
            std::vector<std::string> ignored;
            buildWorld(readSceneFile(sceneFile), ignored);
        } catch (const Error& e) {
            return e.what();
        }
        return "accepted";
    };
    const std::string file = (folder.path / "state.csv").string();
    std::string message = refusedWith("");
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find("cannot read"), std::string::npos) << message;
    message = refusedWith("x,y,z\n1,2,3\n");
    EXPECT_NE(message.find(file + ":1"), std::string::npos) << message;
    EXPECT_NE(message.find("header"), std::string::npos) << message;
    message = refusedWith(good.substr(0, good.rfind('\n', good.size() - 2) + 1));
    EXPECT_NE(message.find(file + ":216"), std::string::npos) << message;  // its last row
    EXPECT_NE(message.find("215 rows for a membrane of 216 vertices"), std::string::npos) << message;
    message = refusedWith(good + "0,0,0,0,0,0\n");
    EXPECT_NE(message.find(file + ":218"), std::string::npos) << message;  // the first row too many
    EXPECT_NE(message.find("217 rows"), std::string::npos) << message;
    EXPECT_EQ(refusedWith(good + "\n\n"), "accepted");  // (blank lines hold no vertex)
    std::string word = good;
    word.replace(word.find('\n') + 1, 1, "a");  // the first row's x
    message = refusedWith(word);
    EXPECT_NE(message.find(file + ":2"), std::string::npos) << message;
    EXPECT_NE(message.find("column 'x'"), std::string::npos) << message;
    std::string nan = good;
    const size_t third = nan.find('\n', nan.find('\n', nan.find('\n') + 1) + 1) + 1;  // line 4
    nan.replace(third, nan.find(',', third) - third, "nan");
    message = refusedWith(nan);
    EXPECT_NE(message.find(file + ":4"), std::string::npos) << message;
    EXPECT_NE(message.find("not a finite number"), std::string::npos) << message;
    EXPECT_EQ(refusedWith(good), "accepted");
}
