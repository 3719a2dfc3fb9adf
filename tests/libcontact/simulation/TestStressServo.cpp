// Stress-controlled walls: the servo law itself (gain, limit speed, area from the walls around
// it), and the physics: one sphere pressed between a servo wall and a fixed wall settles where
// the wall's force is σ·A and the penetrations are those of the closed form P = π·kn*·R·δ²
// (adapted formulation, sphere on a plane; TestPlaneContact), and the wall then holds σ.
// Units: mm, N, s, tonne.
#include "lsdem/simulation/StressServo.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace lsdem;

namespace {

Boundary planeAt(const Vec3& point, const Vec3& normal)
{
    Boundary b;
    b.plane.point = point;
    b.plane.normal = normal;
    return b;
}

/// A cuboid cell [0, 4] × [0, 3] × [0, 2] of six walls facing inwards; the top one a servo
/// wall whose area comes from the four side walls.
World cuboidCell()
{
    World w;
    w.boundaries = {planeAt(Vec3(0, 0, 0), Vec3::UnitX()),  planeAt(Vec3(4, 0, 0), -Vec3::UnitX()),
                    planeAt(Vec3(0, 0, 0), Vec3::UnitY()),  planeAt(Vec3(0, 3, 0), -Vec3::UnitY()),
                    planeAt(Vec3(0, 0, 0), Vec3::UnitZ()),  planeAt(Vec3(0, 0, 2), -Vec3::UnitZ())};
    StressServo& s = w.boundaries[5].servo;
    s.targetStress = 2.0;
    s.areaWalls = {0, 1, 2, 3};
    s.maxSpeed = 10.0;
    s.gain = 0.5;
    return w;
}

} // namespace

// The area follows the side walls as they move; the stress is the normal force over it.
TEST(StressServo, AreaFromTheWallsAroundItFollowsThem)
{
    World w = cuboidCell();
    Boundary& top = w.boundaries[5];
    EXPECT_DOUBLE_EQ(servoArea(w, top), 12.0);
    w.boundaries[1].displacement = Vec3(-1.0, 0, 0);  // the +x wall moves in by 1
    w.boundaries[2].displacement = Vec3(0, 0.5, 0);   // the −y wall moves in by 0.5
    EXPECT_DOUBLE_EQ(servoArea(w, top), 3.0 * 2.5);
    top.force = Vec3(0.3, 0, 15.0);  // grains push it up (against its normal −z)
    EXPECT_DOUBLE_EQ(normalStress(top, 7.5), 2.0);
    top.servo.area = 5.0;
    top.servo.areaWalls = {-1, -1, -1, -1};
    EXPECT_DOUBLE_EQ(servoArea(w, top), 5.0);
}

// v = α·(σ_target − σ)·A/(K·Δt + C) along the normal, clamped to ±v_max; without contacts
// ±v_max.
TEST(StressServo, VelocityIsTheProportionalLawWithALimit)
{
    World w = cuboidCell();
    Boundary& top = w.boundaries[5];
    const double dt = 1e-3;
    // No contact: towards the grains at the limit speed.
    EXPECT_TRUE(servoVelocity(w, top, dt).isApprox(Vec3(0, 0, -10.0)));
    // σ = 1.5 (18 N over 12), K = 1e4: v = 0.5·0.5·12/(1e4·1e-3) = 0.3 along the normal.
    top.force = Vec3(0, 0, 18.0);
    top.normalStiffness = 1e4;
    EXPECT_NEAR(servoVelocity(w, top, dt).z(), -0.3, 1e-15);
    EXPECT_EQ(servoVelocity(w, top, dt).x(), 0.0);
    // Viscous dashpots C respond to the velocity at once: v = α·Δσ·A/(K·Δt + C).
    top.normalDashpot = 20.0;
    EXPECT_NEAR(servoVelocity(w, top, dt).z(), -0.5 * 0.5 * 12.0 / 30.0, 1e-15);
    top.normalDashpot = 0.0;
    // Over-stressed: it backs off.
    top.force = Vec3(0, 0, 30.0);
    EXPECT_NEAR(servoVelocity(w, top, dt).z(), 0.5 * 0.5 * 12.0 / 10.0, 1e-15);
    // A large error is capped at the limit speed, either way.
    top.force = Vec3(0, 0, 3000.0);
    EXPECT_DOUBLE_EQ(servoVelocity(w, top, dt).z(), 10.0);
    top.force = Vec3(0, 0, 1e-9);
    top.normalStiffness = 1.0;
    EXPECT_DOUBLE_EQ(servoVelocity(w, top, dt).z(), -10.0);
    // Only servo walls are driven.
    updateServoVelocities(w, dt);
    EXPECT_DOUBLE_EQ(w.boundaries[5].velocity.z(), -10.0);
    for (int b = 0; b < 5; ++b) EXPECT_TRUE(w.boundaries[size_t(b)].velocity.isZero(0.0)) << b;
}

namespace {

constexpr double kRadius = 5.0;   // mm
constexpr double kKnStar = 1e3;   // N/mm³
constexpr double kDensity = 2.65e-9;  // t/mm³ (quartz)

const std::shared_ptr<const GrainAsset>& sphereAsset()
{
    static const std::shared_ptr<const GrainAsset> asset = [] {
        BakeOptions o;
        o.voxelSize = 0.25;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 8000;
        std::vector<std::string> warnings;
        return std::make_shared<const GrainAsset>(
            bakeAnalytic(AnalyticShape::sphere(kRadius), o, warnings));
    }();
    return asset;
}

/// One free sphere on a fixed floor (z = 0), a servo wall touching its top, no gravity; damped
/// globally (non-viscous) or, if @a restitution < 1, by viscous contact dashpots.
Scene pressedSphereScene(double stress, double area, double maxSpeed, double restitution)
{
    Scene s;
    AssetSpec a;
    a.name = "ball";
    a.loaded = sphereAsset();
    s.assets.push_back(a);
    MaterialSpec m;
    m.name = "quartz";
    m.density = kDensity;
    s.materials.push_back(m);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = kKnStar;
    c.model.damping = ViscousDamping(restitution);
    s.contacts.push_back(c);
    GrainSpec g;
    g.pose.position = Vec3(0, 0, kRadius);
    g.pose.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
    s.grains.push_back(g);
    BoundarySpec floor;
    floor.name = "floor";
    s.boundaries.push_back(floor);
    BoundarySpec top;
    top.name = "top";
    top.point = Vec3(0, 0, 2.0 * kRadius + 0.02);
    top.normal = -Vec3::UnitZ();
    top.servo.targetStress = stress;
    top.servo.area = area;
    top.servo.maxSpeed = maxSpeed;
    s.boundaries.push_back(top);
    s.globalDamping = restitution < 1.0 ? 0.0 : 0.3;
    return s;
}

} // namespace

// The target force σ·A = π·kn*·R·δ² with δ = 0.15 mm (cap radius 1.7 mm, ~110 nodes of the
// 8000 in contact on each side). At rest the wall carries σ·A, the floor the same, and the
// sphere is pressed into each by δ: the gap between the walls is 2R − 2δ. The node quadrature
// of the cap is good to ~2 % in force at N = 8000 (TestPlaneContact), so to ~1 % in δ ∝ √P:
// the band is 1 % of 2δ (measured: 0.04 %). Once settled the wall holds its stress to 0.1 %
// (what is left of the damped vibration); its force is within 0.1 % of σ·A too, and so is the
// floor's. The same with viscous contact damping instead of global damping: the dashpots
// respond to the wall's own speed at once, which the gain accounts for (K·Δt + C).
TEST(StressServo, SpherePressedBetweenAServoWallAndAFloorSettlesAtTheClosedForm)
{
    for (const double restitution : {1.0, 0.5}) {
        SCOPED_TRACE(restitution < 1.0 ? "contact dashpots" : "global damping");
        const double delta = 0.15;
        const double force = kPi * kKnStar * kRadius * delta * delta;
        const double area = 100.0;
        const double stress = force / area;
        std::vector<std::string> warnings;
        World w = buildWorld(pressedSphereScene(stress, area, 20.0, restitution), warnings);
        // The step: a twentieth of the period of the sphere between the two contacts at δ.
        const double contactStiffness = 2.0 * kPi * kKnStar * kRadius * delta;
        const double period =
            2.0 * kPi * std::sqrt(w.grains[0].body.mass / (2.0 * contactStiffness));
        Simulation sim(std::move(w), period / 20.0);
        const Boundary& top = sim.world().boundaries[1];
        const Boundary& floor = sim.world().boundaries[0];
        const int settle = 6000, hold = 3000;
        for (int k = 0; k < settle; ++k) sim.step();
        double worst = 0.0;
        for (int k = 0; k < hold; ++k) {
            sim.step();
            worst = std::max(worst, std::abs(normalStress(top, area) / stress - 1.0));
        }
        const double gap = top.referencePoint().z() - floor.referencePoint().z();
        const double penetration = 2.0 * kRadius - gap;
        std::cout << "[ measured ] servo sphere (restitution " << restitution
                  << "): stress/target = " << normalStress(top, area) / stress << " (worst over "
                  << hold << " steps " << worst << "), floor force/σA = "
                  << -floor.force.z() / force
                  << ", penetration/closed form = " << penetration / (2.0 * delta) << "\n";
        EXPECT_LT(worst, 1e-3);
        EXPECT_NEAR(top.force.z() / force, 1.0, 1e-3);  // the grain pushes it up
        EXPECT_NEAR(-floor.force.z() / force, 1.0, 1e-3);
        EXPECT_NEAR(penetration / (2.0 * delta), 1.0, 0.01);
    }
}
