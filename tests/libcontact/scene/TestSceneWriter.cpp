// The scene writer: what it writes reads back (through the real reader) to the same scene, for
// the bundled examples and for a scene that uses every feature the writer knows, including the
// ones a hand-made writer got wrong (plane boundaries, a formulation per contact, names that
// need escaping); assets held only in memory and non-finite numbers are refused.
#include "lsdem/scene/SceneWriter.h"

#include "lsdem/core/Error.h"
#include "lsdem/scene/SceneFile.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

using namespace lsdem;
using namespace lsdem::test;

namespace {

const std::string kScenes = std::string(LSDEM_SOURCE_DIR) + "/assets/scenes/";

/// Unit vectors and quaternions are normalised again when read: equal to round-off.
template <typename Vector>
void expectSameDirection(const Vector& a, const Vector& b, const std::string& what)
{
    EXPECT_LE((a - b).norm(), 1e-15) << what;
}

// Long by nature: one comparison per field of a Scene.
void expectSameScene(const Scene& a, const Scene& b)
{
    EXPECT_EQ(a.units.length, b.units.length);
    EXPECT_EQ(a.units.mass, b.units.mass);
    EXPECT_EQ(a.units.time, b.units.time);
    EXPECT_EQ(a.units.force, b.units.force);
    ASSERT_EQ(a.assets.size(), b.assets.size());
    for (size_t i = 0; i < a.assets.size(); ++i) {
        const AssetSpec &x = a.assets[i], &y = b.assets[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.file, y.file);
        EXPECT_EQ(x.meshFile, y.meshFile);
        ASSERT_EQ(x.shape.has_value(), y.shape.has_value());
        if (x.shape) {
            EXPECT_EQ(x.shape->kind, y.shape->kind);
            EXPECT_EQ(x.shape->size, y.shape->size);
        }
        if (x.file.empty()) {
            EXPECT_EQ(x.bake.voxelSize, y.bake.voxelSize);
            EXPECT_EQ(x.bake.nodePlacement, y.bake.nodePlacement);
            EXPECT_EQ(x.bake.nodeSpacing, y.bake.nodeSpacing);
            EXPECT_EQ(x.bake.nodeCount, y.bake.nodeCount);
            EXPECT_EQ(x.bake.areaRule, y.bake.areaRule);
            EXPECT_EQ(x.bake.nodeLayout, y.bake.nodeLayout);
        }
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].name, b.materials[i].name);
        EXPECT_EQ(a.materials[i].density, b.materials[i].density);
    }
    ASSERT_EQ(a.contacts.size(), b.contacts.size());
    for (size_t i = 0; i < a.contacts.size(); ++i) {
        const ContactSpec &x = a.contacts[i], &y = b.contacts[i];
        EXPECT_EQ(x.materialA, y.materialA);
        EXPECT_EQ(x.materialB, y.materialB);
        EXPECT_EQ(x.model.formulation, y.model.formulation) << "contact " << i;
        EXPECT_EQ(x.model.testing, y.model.testing);
        EXPECT_EQ(x.model.quadrature, y.model.quadrature) << "contact " << i;
        EXPECT_EQ(x.model.normalStiffness, y.model.normalStiffness);
        EXPECT_EQ(x.model.shearStiffness, y.model.shearStiffness);
        EXPECT_EQ(x.model.friction, y.model.friction);
        EXPECT_EQ(x.model.damping.restitution(), y.model.damping.restitution());
    }
    ASSERT_EQ(a.grains.size(), b.grains.size());
    for (size_t i = 0; i < a.grains.size(); ++i) {
        const GrainSpec &x = a.grains[i], &y = b.grains[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.asset, y.asset);
        EXPECT_EQ(x.material, y.material);
        EXPECT_EQ(x.pose.position, y.pose.position);
        expectSameDirection<Eigen::Vector4d>(x.pose.orientation.coeffs(), y.pose.orientation.coeffs(),
                            "orientation of grain " + std::to_string(i));
        EXPECT_EQ(x.velocity, y.velocity);
        EXPECT_EQ(x.angularVelocity, y.angularVelocity);
        EXPECT_EQ(x.mass, y.mass);
        EXPECT_EQ(x.motion, y.motion);
    }
    ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
    for (size_t i = 0; i < a.boundaries.size(); ++i) {
        const BoundarySpec &x = a.boundaries[i], &y = b.boundaries[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.shape, y.shape) << x.name;
        EXPECT_EQ(x.material, y.material);
        EXPECT_EQ(x.point, y.point);
        expectSameDirection(x.normal, y.normal, "normal of " + x.name);
        EXPECT_EQ(x.extentU, y.extentU);
        EXPECT_EQ(x.extentV, y.extentV);
        if (x.extentU > 0.0) expectSameDirection(x.axisU, y.axisU, "axis_u of " + x.name);
        EXPECT_EQ(x.thickness, y.thickness);
        EXPECT_EQ(x.center, y.center);
        EXPECT_EQ(x.radius, y.radius);
        if (x.shape == BoundaryShape::Cylinder || x.shape == BoundaryShape::Orifice)
            expectSameDirection(x.axis, y.axis, "axis of " + x.name);
        EXPECT_EQ(x.asset, y.asset);
        EXPECT_EQ(x.pose.position, y.pose.position);
        expectSameDirection<Eigen::Vector4d>(x.pose.orientation.coeffs(), y.pose.orientation.coeffs(),
                            "orientation of " + x.name);
        EXPECT_EQ(x.velocity, y.velocity);
        EXPECT_EQ(x.servo.targetStress, y.servo.targetStress) << x.name;
        EXPECT_EQ(x.servo.area, y.servo.area) << x.name;
        EXPECT_EQ(x.servo.areaWalls, y.servo.areaWalls) << x.name;
        EXPECT_EQ(x.servo.gain, y.servo.gain) << x.name;
        EXPECT_EQ(x.servo.maxSpeed, y.servo.maxSpeed) << x.name;
    }
    EXPECT_EQ(a.gravity, b.gravity);
    EXPECT_EQ(a.globalDamping, b.globalDamping);
    EXPECT_EQ(a.timeStep.fixed, b.timeStep.fixed);
    EXPECT_EQ(a.timeStep.safety, b.timeStep.safety);
    EXPECT_EQ(a.end.time, b.end.time);
    EXPECT_EQ(a.end.steps, b.end.steps);
    EXPECT_EQ(a.end.boundary, b.end.boundary);
    EXPECT_EQ(a.end.displacement, b.end.displacement);
    EXPECT_EQ(a.output.historyEvery, b.output.historyEvery);
    EXPECT_EQ(a.output.historyPeriod, b.output.historyPeriod);
    EXPECT_EQ(a.output.vtkPeriod, b.output.vtkPeriod);
    EXPECT_EQ(a.output.checkpointPeriod, b.output.checkpointPeriod);
    EXPECT_EQ(a.output.contactForces, b.output.contactForces);
}

/// Write @a scene into @a dir as scene.toml and read it back with the real reader.
Scene roundTrip(const Scene& scene, const ScratchDir& dir)
{
    const std::string path = dir.file("scene.toml");
    writeSceneFile(scene, path, "written by TestSceneWriter\nsecond line");
    return readSceneFile(path);
}

/// A scene with every feature the writer knows, in a folder with a baked-looking asset file.
/// Long by nature: one entry per feature.
Scene everyFeature(const ScratchDir& dir)
{
    Scene s;
    s.units = {"m", "kg", "s", "N"};
    // The reader checks that files exist; their contents are not read until a world is built.
    std::ofstream(dir.file("grain file.vdb")) << "x";
    AssetSpec file;
    file.name = "baked";
    file.file = dir.file("grain file.vdb");
    AssetSpec sphere;
    sphere.name = "ball";
    sphere.shape = AnalyticShape::sphere(0.1);
    sphere.bake.voxelSize = 0.01;
    sphere.bake.nodePlacement = NodePlacement::Count;
    sphere.bake.nodeCount = 300;
    AssetSpec box;
    box.name = "brick";
    box.shape = AnalyticShape::box(0.3, 0.2, 0.1);
    box.bake.voxelSize = 0.0125;
    box.bake.nodeSpacing = 0.03;
    box.bake.areaRule = AreaRule::Uniform;
    std::ofstream(dir.file("pebble.obj")) << "x";  // (as the .vdb above: not read here)
    AssetSpec pebble;
    pebble.name = "pebble";
    pebble.meshFile = dir.file("pebble.obj");
    pebble.bake.voxelSize = 0.01;
    pebble.bake.nodeSpacing = 0.02;
    pebble.bake.nodeLayout = NodeLayout::Centroidal;
    s.assets = {file, sphere, box, pebble};
    s.materials = {{"sand", 2650.0}, {"steel \"S355\"", 7850.0}, {"rigid", 0.0}};
    auto contact = [](int a, int b, Formulation f, double kn) {
        ContactSpec c;
        c.materialA = a;
        c.materialB = b;
        c.model.formulation = f;
        c.model.normalStiffness = kn;
        return c;
    };
    ContactSpec sandSand = contact(0, 0, Formulation::Adapted, 1e9);
    sandSand.model.shearStiffness = 4e8;
    sandSand.model.friction = 0.5;
    sandSand.model.damping = ViscousDamping(0.3);
    ContactSpec sandSteel = contact(0, 1, Formulation::Original, 1e6);
    sandSteel.model.testing = NodeTesting::OneWay;
    s.contacts = {sandSand, sandSteel, contact(0, 2, Formulation::Volume, 2e9),
                  contact(1, 1, Formulation::SingleNode, 3e5),
                  contact(1, 2, Formulation::Adapted, 0.1)};
    GrainSpec free;
    free.name = "grain \"one\" \\ ünï";
    free.asset = 1;
    free.material = 0;
    free.pose.position = Vec3(0.1, -0.2, 1.0 / 3.0);
    free.pose.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    free.velocity = Vec3(1e-7, 0, -2.5);
    free.angularVelocity = Vec3(0, 3, 0);
    free.mass = 0.0123;
    GrainSpec fixed;
    fixed.asset = 0;
    fixed.material = 1;
    fixed.motion = GrainMotion::Fixed;
    fixed.pose.position = Vec3(1, 1, 1);
    GrainSpec prescribed = fixed;
    prescribed.name = "driver";
    prescribed.asset = 2;
    prescribed.motion = GrainMotion::Prescribed;
    prescribed.velocity = Vec3(0, 0, -0.01);
    prescribed.angularVelocity = Vec3(0.5, 0, 0);
    s.grains = {free, fixed, prescribed};
    BoundarySpec floor;
    floor.name = "floor";
    floor.shape = BoundaryShape::Plane;
    floor.material = 2;
    floor.point = Vec3(0, 0, -0.5);
    floor.normal = Vec3(0, 0.6, 0.8);
    BoundarySpec patch = floor;
    patch.name = "patch";
    patch.point = Vec3(0.5, 0, 0);
    patch.normal = Vec3(-1, 0, 0);
    patch.extentU = 0.4;
    patch.extentV = 0.7;
    patch.axisU = Vec3(0, 0, 1);
    patch.thickness = 0.05;
    patch.velocity = Vec3(-0.001, 0, 0);
    BoundarySpec indenter;
    indenter.name = "indenter";
    indenter.shape = BoundaryShape::Sphere;
    indenter.material = 2;
    indenter.center = Vec3(0, 0, 2);
    indenter.radius = 0.25;
    indenter.velocity = Vec3(0, 0, -0.1);
    BoundarySpec obstacle;
    obstacle.name = "obstacle";
    obstacle.shape = BoundaryShape::LevelSet;
    obstacle.material = 2;
    obstacle.asset = 0;
    obstacle.pose.position = Vec3(3, 0, 0);
    obstacle.pose.orientation = Quat(Eigen::AngleAxisd(0.25, Vec3::UnitZ()));
    // Servo walls: one over a given area, one whose area is bounded by two pairs of walls
    // perpendicular to it (and to each other).
    BoundarySpec lid = floor;
    lid.name = "lid";
    lid.point = Vec3(0, 1.2, 1.6);
    lid.normal = Vec3(0, -0.6, -0.8);
    lid.servo.targetStress = 1e5;
    lid.servo.area = 0.25;
    lid.servo.maxSpeed = 0.01;
    BoundarySpec press = lid;
    press.name = "press";
    press.servo.area = 0.0;
    press.servo.gain = 0.3;
    BoundarySpec x0 = floor, x1 = floor, w0 = floor, w1 = floor;
    x0.name = "x0", x0.point = Vec3(-1, 0, 0), x0.normal = Vec3(1, 0, 0);
    x1.name = "x1", x1.point = Vec3(1, 0, 0), x1.normal = Vec3(-1, 0, 0);
    w0.name = "w0", w0.point = Vec3(0, -0.8, 0.6), w0.normal = Vec3(0, 0.8, -0.6);
    w1.name = "w1", w1.point = Vec3(0, 0.8, -0.6), w1.normal = Vec3(0, -0.8, 0.6);
    press.servo.areaWalls = {4, 5, 6, 7};
    press.areaWallNames = {"x0", "x1", "w0", "w1"};
    BoundarySpec drum;
    drum.name = "drum";
    drum.shape = BoundaryShape::Cylinder;
    drum.material = 2;
    drum.center = Vec3(0.5, -0.25, 0);
    drum.axis = Vec3(0, 0.6, 0.8);
    drum.radius = 4.5;
    BoundarySpec orifice;
    orifice.name = "orifice";
    orifice.shape = BoundaryShape::Orifice;
    orifice.material = 2;
    orifice.center = Vec3(0.25, 0, -1);
    orifice.axis = Vec3(0, 0.6, 0.8);
    orifice.radius = 1.75;
    orifice.thickness = 0.5;
    s.boundaries = {floor, patch, indenter, obstacle, x0, x1, w0, w1, lid, press, drum, orifice};
    s.gravity = Vec3(0, 0, -9.81);
    s.globalDamping = 0.2;
    s.timeStep.safety = 0.15;
    s.end.time = 2.5;
    s.end.steps = 1000000;
    s.end.boundary = 2;
    s.end.displacement = 0.1;
    s.output.historyPeriod = 1e-3;
    s.output.vtkPeriod = 0.05;
    s.output.checkpointPeriod = 0.5;
    s.output.contactForces = false;
    return s;
}

} // namespace

TEST(SceneWriter, BundledScenesReadBackTheSame)
{
    for (const char* name : {"bounce.toml", "settle.toml", "cube27.toml", "servo.toml"}) {
        SCOPED_TRACE(name);
        const Scene original = readSceneFile(kScenes + name);
        // Written beside the original, so relative asset paths stay what they were.
        const ScratchDir dir;
        const std::string text = sceneToToml(original, kScenes);
        expectSameScene(original, parseScene(text, kScenes + "written.toml"));
        // And written elsewhere: paths outside the folder are written absolute.
        expectSameScene(original, roundTrip(original, dir));
    }
}

TEST(SceneWriter, EveryFeatureReadsBackTheSame)
{
    const ScratchDir dir;
    const Scene scene = everyFeature(dir);
    const Scene back = roundTrip(scene, dir);
    expectSameScene(scene, back);
    // The asset below the scene's folder is written relative to it; the header is a comment.
    const std::string text = sceneToToml(scene, dir.path().string(), "a header");
    EXPECT_NE(text.find("file = 'grain file.vdb'"), std::string::npos) << text;
    EXPECT_EQ(text.rfind("# a header\n", 0), 0u) << text;
}

// quadrature = "patch" is written where a contact has it and reads back; node quadrature, the
// default, is not written at all (so scenes written before it existed read back the same).
TEST(SceneWriter, PatchQuadratureIsWrittenAndReadBack)
{
    const ScratchDir dir;
    Scene scene = everyFeature(dir);
    const std::string plain = sceneToToml(scene, dir.path().string());
    EXPECT_EQ(plain.find("quadrature"), std::string::npos) << plain;
    ASSERT_EQ(scene.contacts[4].model.formulation, Formulation::Adapted);
    scene.contacts[4].model.quadrature = NodeQuadrature::Patch;
    const std::string text = sceneToToml(scene, dir.path().string());
    const size_t at = text.find("quadrature = 'patch'");
    ASSERT_NE(at, std::string::npos) << text;
    EXPECT_EQ(text.find("quadrature", at + 1), std::string::npos) << text;  // that contact only
    const Scene back = roundTrip(scene, dir);
    expectSameScene(scene, back);
    EXPECT_EQ(back.contacts[4].model.quadrature, NodeQuadrature::Patch);
    EXPECT_EQ(back.contacts[0].model.quadrature, NodeQuadrature::Point);
    // Written again, the same text.
    EXPECT_EQ(sceneToToml(back, dir.path().string()), text);
}

TEST(SceneWriter, NumbersAreShortAndExact)
{
    const ScratchDir dir;
    Scene scene = everyFeature(dir);
    scene.gravity = Vec3(0.1, 1e-300, 5e-324);  // a denormal reads back too
    scene.grains[0].pose.position = Vec3(1.0 / 3.0, 2.0 / 3.0, 0.30000000000000004);
    const std::string text = sceneToToml(scene, dir.path().string());
    EXPECT_NE(text.find("gravity = [0.1, 1e-300, 5e-324]"), std::string::npos) << text;
    const Scene back = roundTrip(scene, dir);
    EXPECT_EQ(back.gravity, scene.gravity);
    EXPECT_EQ(back.grains[0].pose.position, scene.grains[0].pose.position);
}

TEST(SceneWriter, RefusesWhatItCannotWrite)
{
    const ScratchDir dir;
    Scene scene = everyFeature(dir);
    scene.assets[0].file.clear();
    scene.assets[0].loaded = std::make_shared<const GrainAsset>();
    try {
        sceneToToml(scene, dir.path().string());
        FAIL() << "an asset held only in memory was written";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("only in memory"), std::string::npos) << e.what();
    }
    scene = everyFeature(dir);
    scene.gravity.z() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(sceneToToml(scene, dir.path().string()), Error);
    // Nothing half-written: the failed write leaves no file (and no temporary) behind.
    const size_t before = dir.entryCount();
    EXPECT_THROW(writeSceneFile(scene, dir.file("bad.toml")), Error);
    EXPECT_EQ(dir.entryCount(), before);
}
