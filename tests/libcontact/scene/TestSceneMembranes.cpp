// [[membranes]] in scene files: a tube is read as given, built stretched round with its rims
// held by the nearest named planes, written back the same, and every bad entry is refused
// naming its line, key and fix.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>

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
