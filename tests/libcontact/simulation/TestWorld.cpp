// The World's small amount of behaviour: the contact model of a pair of materials (whichever
// order they come in), and a grain's angular velocity and freedom per kind of motion.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/World.h"

#include <gtest/gtest.h>

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
    c.restitution = 0.5;
    scene.contacts.push_back(c);
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    ASSERT_EQ(w.materialCount, 3);
    for (const auto& [a, b] : {std::pair{0, 2}, std::pair{2, 0}}) {
        EXPECT_EQ(w.model(a, b).formulation, Formulation::Original);
        EXPECT_EQ(w.model(a, b).normalStiffness, 7.0);
        EXPECT_EQ(w.model(a, b).dampingRatio, dampingRatioFromRestitution(0.5));
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
