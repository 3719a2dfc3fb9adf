// The dissipated energy split by mechanism (DissipatedEnergy, Energies): friction, the
// contacts' dashpots and global damping, each against what its motion must have cost by a
// closed form, and their sum against the energy balance the run keeps independently
// (Energies::dissipated: boundary work − the change of kinetic + elastic + potential).
// Units: mm, N, s, tonne.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>

using namespace lsdem;

namespace {

constexpr double kSteel = 7.85e-9;  // t/mm³
constexpr double kKnStar = 1e3;     // N/mm³
constexpr double kG = 9810.0;       // mm/s²

std::shared_ptr<const GrainAsset> baked(const AnalyticShape& shape, int nodes)
{
    BakeOptions o;
    o.voxelSize = 0.25;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = nodes;
    std::vector<std::string> warnings;
    return std::make_shared<const GrainAsset>(bakeAnalytic(shape, o, warnings));
}

/// The 10 × 8 × 4 box of TestSimulation's incline (structured faces), baked once.
std::shared_ptr<const GrainAsset> box()
{
    static const auto asset = baked(AnalyticShape::box(10.0, 8.0, 4.0), 1200);
    return asset;
}

std::shared_ptr<const GrainAsset> sphere()
{
    static const auto asset = baked(AnalyticShape::sphere(5.0), 2000);
    return asset;
}

/// One steel grain of @a asset at @a position moving at @a velocity, above a floor z = 0 when
/// @a floor, under the adapted law (kn* 1e3, ks* 500) with friction @a mu and restitution @a e.
World oneGrain(std::shared_ptr<const GrainAsset> asset, const Vec3& position,
               const Vec3& velocity, double mu, double e, bool floor)
{
    Scene s;
    AssetSpec a;
    a.name = "body";
    a.loaded = std::move(asset);
    a.where = "TestEnergySplit";
    s.assets.push_back(a);
    MaterialSpec steel;
    steel.name = "steel";
    steel.density = kSteel;
    s.materials.push_back(steel);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = kKnStar;
    c.model.shearStiffness = mu > 0.0 ? 500.0 : 0.0;
    c.model.friction = mu;
    c.model.damping = ViscousDamping(e);
    s.contacts.push_back(c);
    GrainSpec g;
    g.pose.position = position;
    g.velocity = velocity;
    s.grains.push_back(g);
    if (floor) {
        BoundarySpec b;
        b.name = "floor";
        b.shape = BoundaryShape::Plane;
        b.point = Vec3::Zero();
        b.normal = Vec3::UnitZ();
        s.boundaries.push_back(b);
    }
    std::vector<std::string> warnings;
    return buildWorld(s, warnings);
}

/// dt: a 60th of the period of the box's face on the floor (K ≈ kn*·80 mm²).
double faceStep(const World& w)
{
    return 2.0 * kPi * std::sqrt(w.grains[0].body.mass / (kKnStar * 80.0)) / 60.0;
}

} // namespace

// A box sliding face-down on a level floor (μ = 0.5, no dashpot) stops after v0²/(2μg): every
// node slides, so friction is μ·m·g and its work is μ·m·g·s over the slide s, all of ½·m·v0².
// The split must find that energy under friction and nothing under the other mechanisms. What
// stays in the shear springs once the box sticks, (μ·m·g)²/(2·ks*·80 mm²), is 4e-6 of ½·m·v0².
// Released just touching and undamped, the box bounces on its face all the while, its normal
// force swinging between 0 and 2·m·g every 60 steps, so each node's Coulomb limit moves within
// every step: counted at the step's end limit instead of across it (see updateShearForce), the
// friction came out 2 % high; as counted, 0.06 %. 0.5 % holds it with room and catches that.
TEST(EnergySplit, FrictionTakesTheKineticEnergyOfASlidingBox)
{
    const double v0 = 20.0, mu = 0.5;
    World w = oneGrain(box(), Vec3(0, 0, 2.0), Vec3(v0, 0, 0), mu, 1.0, true);
    w.gravity = Vec3(0, 0, -kG);
    const double dt = faceStep(w);
    Simulation run(std::move(w), dt);
    const Grain& g = run.world().grains[0];
    const double slideTime = v0 / (mu * kG);
    while (run.world().time < 1.5 * slideTime) run.step();
    const double mass = g.body.mass, kinetic0 = 0.5 * mass * v0 * v0;
    const double slide = g.body.pose.position.x();
    const Energies e = run.energies();
    std::cout << "[ measured ] sliding box: friction / ½mv0² = " << e.friction / kinetic0
              << ", friction / μmgs = " << e.friction / (mu * mass * kG * slide)
              << ", slide / (v0²/2μg) = " << slide / (v0 * v0 / (2.0 * mu * kG))
              << ", balance's dissipated / friction = " << e.dissipated / e.friction << "\n";
    EXPECT_LT(std::abs(g.body.velocity.x()), 1e-3 * v0);  // it stopped
    EXPECT_NEAR(slide / (v0 * v0 / (2.0 * mu * kG)), 1.0, 0.005);
    EXPECT_NEAR(e.friction / kinetic0, 1.0, 0.005);
    EXPECT_NEAR(e.friction / (mu * mass * kG * slide), 1.0, 0.005);
    EXPECT_NEAR(e.dissipated / e.friction, 1.0, 0.005);
    EXPECT_EQ(e.dashpot, 0.0);
    EXPECT_EQ(e.globalDamping, 0.0);
}

// A grain dropped on the floor without gravity or friction, restitution e: what the rebound
// lacks, ½·m·(v_in² − v_out²), the dashpot took (the elastic energy is back to zero once the
// grain has left). The box's face is a linear spring, the sphere's cap is not (its dashpot is
// capped so as never to pull); both must balance. The balance itself holds to O((ω·dt)²) (the
// elastic rebound test of TestSimulation measures ≤ 1e-3 of the impact's energy). The dashpot's
// power is weighed with the velocity it saw, the half step's, while its force acts over the two
// half kicks around it: an O(ω·dt) error (ω·dt = 2π/200 here), measured 0.9 % for the box at
// e = 0.5, 0.6 % for the sphere, 0.1 % at e = 0.9. 2 % holds that; a dashpot missed, or counted
// on both grains of a contact, is off by 100 %.
TEST(EnergySplit, DashpotTakesWhatTheReboundLacks)
{
    struct Case
    {
        const char* name;
        std::shared_ptr<const GrainAsset> asset;
        double bottom;     ///< mm from the centroid to the lowest point
        double e;
        double stiffness;  ///< N/mm at the deepest point, for the step
    };
    const double speed = 100.0;
    for (const Case& c : {Case{"box", box(), 2.0, 0.5, kKnStar * 80.0},
                          Case{"box", box(), 2.0, 0.9, kKnStar * 80.0},
                          Case{"sphere", sphere(), 5.0, 0.5, 0.0}}) {
        World w = oneGrain(c.asset, Vec3(0, 0, c.bottom + 1e-4), Vec3(0, 0, -speed), 0.0, c.e,
                           true);
        const double mass = w.grains[0].body.mass;
        // The sphere's stiffness at its deepest, 2π·kn*·R·δ with ½mv² = π·kn*·R·δ³/3.
        const double stiffness =
            c.stiffness > 0.0
                ? c.stiffness
                : 2.0 * kPi * kKnStar * 5.0 *
                      std::cbrt(1.5 * mass * speed * speed / (kPi * kKnStar * 5.0));
        Simulation sim(std::move(w), 2.0 * kPi * std::sqrt(mass / stiffness) / 200.0);
        const Grain& g = sim.world().grains[0];
        bool touched = false;
        for (int k = 0; k < 100000 && !(touched && sim.contactNodes() == 0); ++k) {
            sim.step();
            touched |= sim.contactNodes() > 0;
        }
        ASSERT_TRUE(touched && sim.contactNodes() == 0) << c.name;
        const double out = g.body.velocity.z();
        const double lost = 0.5 * mass * (speed * speed - out * out);
        const Energies e = sim.energies();
        std::cout << "[ measured ] " << c.name << ", e = " << c.e << ": rebound/impact "
                  << out / speed << ", dashpot / lost = " << e.dashpot / lost
                  << ", balance's dissipated / lost = " << e.dissipated / lost << "\n";
        EXPECT_GT(out, 0.0) << c.name;
        EXPECT_NEAR(e.dashpot / lost, 1.0, 0.02) << c.name << " e " << c.e;
        EXPECT_NEAR(e.dissipated / lost, 1.0, 0.01) << c.name << " e " << c.e;
        EXPECT_EQ(e.friction, 0.0);
        EXPECT_EQ(e.globalDamping, 0.0);
    }
}

// A sphere falling from rest with global damping λ: its force m·g is cut to (1 − λ)·m·g against
// the motion, so the damping takes λ·m·g per unit of fall. The step's drift moves the grain by
// v_{n+1/2}·dt, the velocity each evaluation's damping is weighed with, so the sum is the fall's
// λ·m·g·Δz to round-off but for the first half step (undamped: the grain starts at rest), a
// share of 1/(2N²) of N steps. The balance (potential lost − kinetic gained) agrees to O(1/N).
TEST(EnergySplit, GlobalDampingTakesItsShareOfTheWeightsWork)
{
    World w = oneGrain(sphere(), Vec3(0, 0, 100.0), Vec3::Zero(), 0.0, 1.0, false);
    w.gravity = Vec3(0, 0, -kG);
    const double lambda = 0.3;
    w.globalDamping = lambda;
    const int steps = 400;
    Simulation sim(std::move(w), 1e-4);
    for (int k = 0; k < steps; ++k) sim.step();
    const Grain& g = sim.world().grains[0];
    const double fall = 100.0 - g.body.pose.position.z();
    const Energies e = sim.energies();
    const double expected = lambda * g.body.mass * kG * fall;
    std::cout << "[ measured ] damped fall of " << fall << " mm: damping / λmgΔz = "
              << e.globalDamping / expected << ", balance's dissipated / λmgΔz = "
              << e.dissipated / expected << "\n";
    EXPECT_NEAR(e.globalDamping / expected, 1.0, 1.0 / double(steps * steps));
    EXPECT_NEAR(e.dissipated / expected, 1.0, 2.0 / double(steps));
    EXPECT_EQ(e.friction + e.dashpot, 0.0);
}
