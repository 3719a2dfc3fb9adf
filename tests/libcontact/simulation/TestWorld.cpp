// The World's small amount of behaviour: the contact model of a pair of materials (whichever
// order they come in), a grain's angular velocity and freedom per kind of motion, and the
// assets loaded in parallel as one by one.
#include "lsdem/core/Error.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/World.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

using namespace lsdem;

// The table is materialCount² row-major; buildWorld writes a contact of materials (a, b) into
// both (a, b) and (b, a), so the lookup does not depend on which grain comes first.
TEST(World, ModelOfAPairOfMaterialsIsTheSameInEitherOrder)
{
    World hand;
    hand.materialCount = 2;
    hand.models.resize(4);
    for (int k = 0; k < 4; ++k) hand.models[k].normalStiffness = 10.0 + k;
    EXPECT_EQ(hand.model(0, 0).normalStiffness, 10.0);
    EXPECT_EQ(hand.model(0, 1).normalStiffness, 11.0);
    EXPECT_EQ(hand.model(1, 0).normalStiffness, 12.0);
    EXPECT_EQ(hand.model(1, 1).normalStiffness, 13.0);

    Scene scene;
    for (const char* name : {"steel", "rubber", "glass"}) {
        MaterialSpec m;
        m.name = name;
        m.density = 1.0;
        scene.materials.push_back(m);
    }
    ContactSpec c;
    c.materialA = 2;  // given as (glass, steel)
    c.materialB = 0;
    c.model.formulation = Formulation::Original;
    c.model.normalStiffness = 7.0;
    c.model.damping = ViscousDamping(0.5);
    scene.contacts.push_back(c);
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    ASSERT_EQ(w.materialCount, 3);
    for (const auto& [a, b] : {std::pair{0, 2}, std::pair{2, 0}}) {
        EXPECT_EQ(w.model(a, b).formulation, Formulation::Original);
        EXPECT_EQ(w.model(a, b).normalStiffness, 7.0);
        EXPECT_EQ(w.model(a, b).damping.restitution(), 0.5);
    }
    EXPECT_EQ(w.model(0, 1).normalStiffness, 0.0);  // no contact given: the default model
    EXPECT_EQ(w.model(1, 0).normalStiffness, 0.0);
}

// ω of a free grain is R·I⁻¹·Rᵀ·L from its angular momentum; a fixed grain never turns, a
// prescribed one turns at its given rate whatever its angular momentum says.
TEST(World, GrainAngularVelocityFollowsItsMotion)
{
    Grain g;
    g.body.principalInertia = Vec3(1.0, 2.0, 4.0);
    g.body.pose.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, -1, 2).normalized()));
    g.body.angularMomentum = Vec3(0.5, -1.0, 2.0);
    g.prescribedAngularVelocity = Vec3(3.0, 0.0, -1.0);

    const Mat3 r = g.body.pose.orientation.toRotationMatrix();
    const Vec3 bodyL = r.transpose() * g.body.angularMomentum;
    const Vec3 expected = r * Vec3(bodyL.x() / 1.0, bodyL.y() / 2.0, bodyL.z() / 4.0);

    g.motion = GrainMotion::Free;
    EXPECT_TRUE(g.isFree());
    EXPECT_LT((g.angularVelocity() - expected).norm(), 1e-14);
    g.motion = GrainMotion::Fixed;
    EXPECT_FALSE(g.isFree());
    EXPECT_EQ(g.angularVelocity(), Vec3::Zero());
    g.motion = GrainMotion::Prescribed;
    EXPECT_FALSE(g.isFree());
    EXPECT_EQ(g.angularVelocity(), Vec3(3.0, 0.0, -1.0));
}

namespace {

/// A scene asset baked at load: a unit sphere at @a voxel with far more nodes than the voxels
/// resolve, so its bake warns (naming the voxel size).
AssetSpec warningSphere(const std::string& name, double voxel)
{
    AssetSpec a;
    a.name = name;
    a.shape = AnalyticShape::sphere(1.0);
    a.bake.voxelSize = voxel;
    a.bake.nodePlacement = NodePlacement::Count;
    a.bake.nodeCount = 400;  // spacing about 0.18
    return a;
}

} // namespace

// buildWorld loads and bakes the assets in parallel, with the outcome of one by one: each
// asset's warnings in the scene's order, and of several bad assets the first in that order is
// the one reported.
TEST(World, AssetsLoadInParallelAsOneByOne)
{
    Scene scene;
    scene.materials.push_back({"steel", 1.0});
    auto voxelOf = [](int k) { return 0.4 + 0.01 * k; };
    for (int k = 0; k < 6; ++k)
        scene.assets.push_back(warningSphere("s" + std::to_string(k), voxelOf(k)));
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    ASSERT_EQ(w.assets.size(), 6u);
    ASSERT_EQ(warnings.size(), 6u);
    for (int k = 0; k < 6; ++k) {
        EXPECT_EQ(w.assets[size_t(k)]->voxelSize, voxelOf(k));
        std::ostringstream voxel;
        voxel << "voxel size " << voxelOf(k) << ":";
        EXPECT_NE(warnings[size_t(k)].find(voxel.str()), std::string::npos) << warnings[size_t(k)];
    }

    test::ScratchDir dir;
    std::ofstream(dir.file("bad.vdb")) << "not an asset";
    for (int bad : {4, 2}) {
        scene.assets[size_t(bad)].shape.reset();
        scene.assets[size_t(bad)].file = dir.file("bad.vdb");
    }
    try {
        buildWorld(scene, warnings);
        ADD_FAILURE() << "bad assets were loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("asset 's2'"), std::string::npos) << e.what();
    }
}

// A scene built in code (Python, the studies) gets the file reader's check: two materials that
// can meet without a contact law would get the zero model and pass through each other, so
// buildWorld refuses them, saying how to add the law from a file and from Python.
TEST(World, RefusesMaterialsThatMeetWithoutAContactLaw)
{
    Scene scene;
    scene.materials = {{"sand", 1.0}, {"steel", 1.0}};
    scene.assets.push_back(warningSphere("ball", 0.4));
    for (int k = 0; k < 2; ++k) {
        GrainSpec g;
        g.material = k;
        g.pose.position = Vec3(3.0 * k, 0.0, 0.0);
        g.where = "grain " + std::to_string(k);
        scene.grains.push_back(g);
    }
    ContactSpec sandSand;
    sandSand.model.normalStiffness = 1e3;
    scene.contacts.push_back(sandSand);  // sand with sand, but nothing for sand with steel
    std::vector<std::string> warnings;
    try {
        buildWorld(scene, warnings);
        ADD_FAILURE() << "a world was built without a sand-steel law";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("grain 0"), std::string::npos) << what;
        EXPECT_NE(what.find("no contact law between materials 'sand' and 'steel'"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("materials = [\"sand\", \"steel\"]"), std::string::npos) << what;
        EXPECT_NE(what.find("scene.add_contact(\"sand\", \"steel\", normal_stiffness="),
                  std::string::npos)
            << what;
    }

    ContactSpec sandSteel = sandSand;
    sandSteel.materialB = 1;
    scene.contacts.push_back(sandSteel);
    EXPECT_EQ(buildWorld(scene, warnings).model(0, 1).normalStiffness, 1e3);
}
