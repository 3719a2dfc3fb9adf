// The periodic cell (PeriodicCell.h): grains leave through one face and come back through the
// other, and touch the images of grains near the opposite face. The physics must not see the
// faces: a contact across one is the same contact inside; a packing translated by any vector is
// the same world; an elastic gas in a cell keeps its energy and, with no walls, its momentum.
#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneWriter.h"
#include "lsdem/simulation/Micromechanics.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/ls/Bake.h"
#include "lsdem/core/Error.h"

#include "support/TestAssets.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <random>

using namespace lsdem;

namespace {

constexpr double kRadius = 3.0;  // mm (the cell must be at least 4.5 radii)
constexpr double kCell = 20.0;   // mm, each axis

std::shared_ptr<const GrainAsset> sphere()
{
    static const auto asset = lsdem::test::bakedShape(AnalyticShape::sphere(kRadius), 0.1, 1000);
    return asset;
}

/// Spheres at @a positions moving at @a velocities in a cell of kCell along each axis (origin
/// 0), restitution @a e, adapted kn* 1e3 (ks* 500 with @a friction), no gravity.
Scene periodicScene(const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities,
                    double e = 1.0, double friction = 0.0)
{
    Scene s;
    AssetSpec a;
    a.name = "ball";
    a.loaded = sphere();
    a.where = "TestPeriodicCell";
    s.assets.push_back(a);
    MaterialSpec steel;
    steel.name = "steel";
    steel.density = 7.85e-9;
    s.materials.push_back(steel);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = 1e3;
    c.model.damping = ViscousDamping(e);
    c.model.friction = friction;
    c.model.shearStiffness = friction > 0.0 ? 500.0 : 0.0;
    s.contacts.push_back(c);
    for (size_t i = 0; i < positions.size(); ++i) {
        GrainSpec g;
        g.pose.position = positions[i];
        g.velocity = velocities.empty() ? Vec3::Zero() : velocities[i];
        s.grains.push_back(g);
    }
    s.periodicCell = Vec3::Constant(kCell);
    return s;
}

World build(const Scene& scene)
{
    std::vector<std::string> warnings;
    return buildWorld(scene, warnings);
}

/// A gas of 27 spheres on a jittered 3×3×3 lattice filling the cell (gaps of ~0.7 mm between
/// neighbours, across the faces too), with random velocities (seeded): they collide within a
/// few hundred steps.
std::pair<std::vector<Vec3>, std::vector<Vec3>> gas()
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> x, v;
    const double pitch = kCell / 3.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                x.push_back(Vec3(pitch * (i + 0.5), pitch * (j + 0.5), pitch * (k + 0.5)) +
                            0.15 * Vec3(u(rng), u(rng), u(rng)));
                v.push_back(1000.0 * Vec3(u(rng), u(rng), u(rng)));
            }
    return {x, v};
}

} // namespace

TEST(PeriodicCell, ShiftIntoMovesByWholePeriodsAlongPeriodicAxesOnly)
{
    PeriodicCell cell;
    cell.origin = Vec3(-1.0, 0.0, 0.0);
    cell.size = Vec3(10.0, 0.0, 4.0);  // y not periodic
    EXPECT_FALSE(PeriodicCell().active());
    EXPECT_TRUE(cell.active());
    EXPECT_EQ(cell.shiftInto(Vec3(3.0, 50.0, 1.0)), Vec3::Zero());
    EXPECT_EQ(cell.shiftInto(Vec3(9.0, 50.0, -0.5)), Vec3(-10.0, 0.0, 4.0));
    EXPECT_EQ(cell.shiftInto(Vec3(-31.5, -7.0, 8.0)), Vec3(40.0, 0.0, -8.0));  // x to 8.5
    // The upper face belongs to the next period; the lower to this one.
    EXPECT_EQ(cell.shiftInto(Vec3(9.0, 0.0, 0.0)).x(), -10.0);
    EXPECT_EQ(cell.shiftInto(Vec3(-1.0, 0.0, 0.0)).x(), 0.0);
    // Whatever rounding does, the result lies in [origin, origin + size).
    for (double x : {-1.0 - 1e-17, 9.0 - 1e-15, -1e-300, 1e6 + 0.1, -1e6 - 0.3}) {
        const double inside = x + cell.shiftInto(Vec3(x, 0, 0)).x();
        EXPECT_GE(inside, -1.0) << x;
        EXPECT_LT(inside, 9.0) << x;
    }
}

// Two spheres overlapping by 0.1 mm, once in the middle of the cell and once with the pair cut
// by the face x = 0 (one grain near each side): the same forces and torques, to the rounding of
// positions near 20 mm.
TEST(PeriodicCell, AContactAcrossAFaceIsTheContactInside)
{
    const Vec3 gap(2.0 * kRadius - 0.1, 0.3, -0.2);
    Simulation inside(build(periodicScene({Vec3(8, 10, 10), Vec3(8, 10, 10) + gap}, {})), 1e-7);
    const Vec3 across = Vec3(kCell - 1.0, 10, 10);  // its partner lands near x = 2.9
    Simulation wrapped(build(periodicScene({across, across + gap}, {})), 1e-7);
    const World& w = wrapped.world();
    ASSERT_LT(w.grains[1].body.pose.position.x(), 5.0);  // moved into the cell: apart by ~L
    for (int k = 0; k < 2; ++k) {
        const Grain& a = inside.world().grains[size_t(k)];
        const Grain& b = w.grains[size_t(k)];
        EXPECT_GT(a.force.norm(), 1.0);
        EXPECT_LT((a.force - b.force).norm(), 1e-9 * a.force.norm()) << k;
        EXPECT_LT((a.torque - b.torque).norm(), 1e-9 * a.force.norm()) << k;
    }
    EXPECT_NEAR(inside.elasticEnergy(), wrapped.elasticEnergy(), 1e-9 * inside.elasticEnergy());
    // The contact record gives second's image: the branch vector is the short one.
    const std::vector<ContactRecord> records = wrapped.contactRecords();
    ASSERT_EQ(records.size(), 1u);
    const Vec3 branch = w.grains[size_t(records[0].second)].body.pose.position + records[0].shift -
                        w.grains[size_t(records[0].first)].body.pose.position;
    EXPECT_LT((branch.cwiseAbs() - gap.cwiseAbs()).norm(), 1e-12);
    const Micromechanics m = micromechanicsOf(w, records);
    const Micromechanics reference = micromechanicsOf(inside.world(), inside.contactRecords());
    EXPECT_LT((m.stressMoment - reference.stressMoment).norm(),
              1e-9 * reference.stressMoment.norm());
}

// The gas, and the gas translated by (0.37, −0.61, 0.23) of the cell: many grains now meet as
// images across faces where they met inside, and the other way round; a periodic world has no
// place, so every grain feels the same forces, and 600 steps later each has moved the same (to
// the rounding of positions taken modulo the cell, which collisions amplify a little).
TEST(PeriodicCell, ATranslatedPackingIsTheSameWorld)
{
    auto [x, v] = gas();
    const Vec3 offset = kCell * Vec3(0.37, -0.61, 0.23);
    std::vector<Vec3> moved;
    for (const Vec3& p : x) moved.push_back(p + offset);
    Simulation a(build(periodicScene(x, v)), 1e-6), b(build(periodicScene(moved, v)), 1e-6);
    // (Built, each grain is moved into the cell: where it starts.)
    std::vector<Vec3> startA, startB;
    for (size_t i = 0; i < x.size(); ++i) {
        startA.push_back(a.world().grains[i].body.pose.position);
        startB.push_back(b.world().grains[i].body.pose.position);
    }
    long long contacts = 0, acrossInA = 0, acrossInB = 0;
    for (int k = 0; k < 600; ++k) {
        a.step(), b.step();
        for (const ContactRecord& r : a.contactRecords()) ++contacts, acrossInA += !r.shift.isZero(0.0);
        for (const ContactRecord& r : b.contactRecords()) acrossInB += !r.shift.isZero(0.0);
    }
    double worst = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const Grain& ga = a.world().grains[i];
        const Grain& gb = b.world().grains[i];
        const Vec3 da = ga.unwrappedPosition() - startA[i], db = gb.unwrappedPosition() - startB[i];
        worst = std::max(worst, (da - db).norm());
        EXPECT_LT((ga.body.velocity - gb.body.velocity).norm(), 1e-6) << i;
    }
    std::printf("[ measured ] translated gas: %lld contact-steps, %lld and %lld of them across "
                "faces, largest difference of displacement %.3g mm\n",
                contacts, acrossInA, acrossInB, worst);
    EXPECT_GT(contacts, 300);  // measured: 567
    EXPECT_NE(acrossInA, acrossInB);  // the faces cut other contacts
    EXPECT_LT(worst, 1e-9);
}

// An elastic gas (no friction, no damping, no walls, no gravity), streaming along x through the
// faces as it collides for 3000 steps: the
// kinetic plus elastic energy stays within velocity Verlet's shadow-energy error (~1e-3 of the
// energy at 200 steps per contact period, as the rebound test in TestSimulation measures), and
// the total momentum, which only the contacts across faces could disturb (a force without its
// reaction), to round-off.
TEST(PeriodicCell, AnElasticGasKeepsItsEnergyAndMomentum)
{
    auto [x, v] = gas();
    for (Vec3& velocity : v) velocity.x() += 3000.0;  // streaming through the x faces too
    Simulation sim(build(periodicScene(x, v)), 1e-6);
    const auto momentum = [&] {
        Vec3 p = Vec3::Zero();
        for (const Grain& g : sim.world().grains) p += g.body.mass * g.body.velocity;
        return p;
    };
    const Energies e0 = sim.energies();
    const double total0 = e0.kinetic + e0.elastic, scale = sim.world().grains[0].body.mass * 3000.0;
    const Vec3 p0 = momentum();
    double drift = 0.0;
    long long acrossFaces = 0, contactSteps = 0;
    for (int k = 0; k < 3000; ++k) {
        sim.step();
        const Energies e = sim.energies();
        drift = std::max(drift, std::abs(e.kinetic + e.elastic - total0) / total0);
        for (const ContactRecord& r : sim.contactRecords()) {
            acrossFaces += !r.shift.isZero(0.0);
            ++contactSteps;
        }
    }
    long long wrapped = 0;
    for (const Grain& g : sim.world().grains) wrapped += !g.wrapShift.isZero(0.0);
    std::printf("[ measured ] elastic gas: %lld contact-steps (%lld across faces), %lld grains "
                "wrapped, energy drift %.3g, momentum change %.3g of one grain's\n",
                contactSteps, acrossFaces, wrapped, drift, (momentum() - p0).norm() / scale);
    EXPECT_GT(acrossFaces, 100);
    EXPECT_GT(wrapped, 0);
    EXPECT_LT(drift, 2e-3);
    EXPECT_LT((momentum() - p0).norm(), 1e-9 * scale);
    EXPECT_EQ(sim.energies().dissipated, sim.energies().dissipated);  // finite
}

// The gas on one and on two threads: the same bits.
TEST(PeriodicCell, ResultsAreBitIdenticalOnOneAndTwoThreads)
{
    auto [x, v] = gas();
    const auto run = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        Simulation sim(build(periodicScene(x, v)), 1e-6);
        for (int k = 0; k < 600; ++k) sim.step();
        return sim.world();
    };
    const World one = run(1), two = run(2);
    for (size_t i = 0; i < one.grains.size(); ++i) {
        EXPECT_EQ(one.grains[i].body.pose.position, two.grains[i].body.pose.position) << i;
        EXPECT_EQ(one.grains[i].body.velocity, two.grains[i].body.velocity) << i;
        EXPECT_EQ(one.grains[i].wrapShift, two.grains[i].wrapShift) << i;
    }
}

// The scene: the cell is read and written back, given only when there is one; a cell too small
// for its grains, or with a negative period, is refused naming the key and the fix.
TEST(PeriodicCell, SceneGivesTheCellAndRefusesOneTooSmall)
{
    Scene s = periodicScene({Vec3(1, 1, 1)}, {});
    s.periodicOrigin = Vec3(-1, 0, 0);
    World w = build(s);
    EXPECT_EQ(w.periodic.size, Vec3::Constant(kCell));
    EXPECT_EQ(w.periodic.origin, Vec3(-1, 0, 0));
    s.periodicCell = Vec3(kCell, 0.0, 4.0 * kRadius);
    try {
        build(s);
        ADD_FAILURE() << "a cell of 4 radii was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("periodic_cell: the period along z"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("at least 13.5"), std::string::npos) << e.what();
    }
    const std::string text = R"(
[assets.ball]
shape = "sphere"
radius = 1
voxel = 0.1
nodes = 200
[materials.m]
density = 1e-9
[[contacts]]
materials = ["m", "m"]
normal_stiffness = 1e3
[[grains]]
asset = "ball"
material = "m"
position = [1, 1, 1]
[simulation]
end_steps = 1
periodic_cell = [10, 10, 0]
periodic_origin = [-5, -5, 0]
)";
    const Scene read = parseScene(text, "cell.toml");
    EXPECT_EQ(read.periodicCell, Vec3(10, 10, 0));
    EXPECT_EQ(read.periodicOrigin, Vec3(-5, -5, 0));
    const std::string written = sceneToToml(read, "");
    EXPECT_NE(written.find("periodic_cell = [10.0, 10.0, 0.0]"), std::string::npos) << written;
    EXPECT_EQ(parseScene(written, "again.toml").periodicCell, read.periodicCell);
    // Without a cell, a written scene says nothing of it.
    Scene plain = read;
    plain.periodicCell = plain.periodicOrigin = Vec3::Zero();
    EXPECT_EQ(sceneToToml(plain, "").find("periodic"), std::string::npos);
    std::string negative = text;
    negative.replace(negative.find("[10, 10, 0]"), 11, "[10, -1, 0]");
    try {
        parseScene(negative, "negative.toml");
        ADD_FAILURE() << "a negative period was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("periodic_cell: must be >= 0 in every component"),
                  std::string::npos)
            << e.what();
    }
}

// A deforming cell: a simple cubic lattice of 27 spheres just touching (pitch 2R), compressed
// isotropically at ε̇ by the cell alone (no walls) to ε = −2 %. Each pair of neighbours then
// overlaps by δ = 2R·|ε|, so the Love–Weber stress moment along each axis is −27·a·P(δ) (27
// contacts along each axis, branch a = 2R(1 + ε), P the law's exact continuum force between two
// spheres, SphereContactReference.h). The cap (radius sqrt(R·δ) = 0.6 mm) holds a few nodes of
// the 1000-node ball: as points they give M within 10 % (measured −1.7, −7.5, +1.4 % along x, y,
// z: the node pattern), as patches within 3 % (measured −1.2 to −1.4 %: what is left is the
// other ball's voxel level set, as between two balls elsewhere). The cell's work through the
// contacts is what they store (the law's own elastic energy) plus the little kinetic energy the
// nodes' asymmetries stir up: with points the balance closes to 2.4e-4 of the work (1e-3 allowed;
// a patch's energy is its quadrature's, which leaves 0.4 %). The cell is L₀·(1 + ε̇·dt)^n after
// n steps.
TEST(PeriodicCell, ACompressedLatticeStoresTheCellsWork)
{
    std::vector<Vec3> x;
    const double pitch = 2.0 * kRadius;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) x.push_back(pitch * Vec3(i + 0.5, j + 0.5, k + 0.5));
    const double strain = -0.02, duration = 5e-3, dt = 2e-6;
    const int steps = int(std::lround(duration / dt));
    for (const NodeQuadrature quadrature : {NodeQuadrature::Point, NodeQuadrature::Patch}) {
        const bool patches = quadrature == NodeQuadrature::Patch;
        Scene scene = periodicScene(x, {});
        scene.contacts[0].model.quadrature = quadrature;
        scene.periodicCell = Vec3::Constant(3.0 * pitch);
        scene.periodicStrainRate = Vec3::Constant(strain / duration);
        Simulation sim(build(scene), dt);
        for (int k = 0; k < steps; ++k) sim.step();
        const World& w = sim.world();
        const double stretch = std::pow(1.0 + dt * strain / duration, steps);
        EXPECT_NEAR(w.periodic.size.x() / (3.0 * pitch), stretch, 1e-12);
        const double reached = stretch - 1.0;  // ≈ −2 %
        const double force = exactSphereContactForce(kRadius, -pitch * reached, 1e3);
        const Micromechanics m = micromechanicsOf(w, sim.contactRecords());
        const double expected = -27.0 * pitch * (1.0 + reached) * force;
        const Energies e = sim.energies();
        std::printf("[ measured ] compressed lattice, %s: %lld grain contacts, M / −27·a·P = "
                    "%.4f, %.4f, %.4f; cell work %.5g, elastic %.5g, kinetic %.3g, balance's "
                    "dissipated %.3g\n",
                    patches ? "patches" : "points", m.grainContacts,
                    m.stressMoment(0, 0) / expected, m.stressMoment(1, 1) / expected,
                    m.stressMoment(2, 2) / expected, e.boundaryWork, e.elastic, e.kinetic,
                    e.dissipated);
        EXPECT_EQ(m.grainContacts, 81);
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(m.stressMoment(a, a) / expected, 1.0, patches ? 0.03 : 0.10) << a;
        EXPECT_GT(e.boundaryWork, 0.0);
        EXPECT_LT(std::abs(e.dissipated), (patches ? 1e-2 : 1e-3) * e.boundaryWork);
        EXPECT_LT(e.kinetic, 0.05 * e.boundaryWork);  // compressed slowly: mostly stored
    }
}

// Stress control: the 27 spheres of the gas, at rest and frictional (μ 0.5), in a cell first
// compressed at a set rate until they jam (a mean stress of 0.8 MPa; lower stresses can be
// passing collisions of grains that still dodge each other), then driven on each axis to a compressive stress of 1 MPa
// (global damping settles them). The stress the cell measures is the contacts' Love–Weber
// stress −M_kk/V (micromechanicsOf, to round-off), and once the servo has come to rest it is
// the target on every axis within 2 % (the servo strains at full speed 10 % off the target,
// slower nearer: it stops at the target). Then the z axis is compressed at a set rate (2 % more)
// while x and y keep their 1 MPa: their stress stays within 5 % of it while z's grows.
TEST(PeriodicCell, StressControlReachesAndHoldsItsTargets)
{
    Scene scene = periodicScene(gas().first, {}, 0.5, 0.5);
    scene.globalDamping = 0.3;
    scene.periodicStrainRate = Vec3::Constant(-5.0);
    Simulation sim(build(scene), 2e-6);
    World& w = sim.world();
    while (w.periodic.stress.sum() / 3.0 < 0.8 && w.step < 40000) sim.step();
    ASSERT_LT(w.step, 40000) << "the gas never jammed";
    const long long jammedAt = w.step;
    // Slow enough that the grains follow: the sample's stress answers a strain within a few
    // contact periods (~2e-4 s), in which the servo at full speed strains it 2e-4.
    const double target = 1.0;  // MPa
    w.periodic.strainRate = Vec3::Zero();
    w.periodic.targetStress = Vec3::Constant(target);
    w.periodic.maxStrainRate = Vec3::Constant(1.0);
    for (int k = 0; k < 15000; ++k) sim.step();
    const Micromechanics m = micromechanicsOf(w, sim.contactRecords());
    std::printf("[ measured ] stress control: jammed at step %lld; σ = %.4f, %.4f, %.4f MPa at "
                "step %lld (cell %.4f mm), strain rates %.3g %.3g %.3g\n",
                jammedAt, w.periodic.stress.x(), w.periodic.stress.y(), w.periodic.stress.z(), w.step,
                w.periodic.size.x(), w.periodic.strainRate.x(), w.periodic.strainRate.y(),
                w.periodic.strainRate.z());
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(w.periodic.stress[a], -m.stressMoment(a, a) / w.periodic.volume(),
                    1e-9 * target)
            << a;
        EXPECT_NEAR(w.periodic.stress[a], target, 0.02 * target) << a;
    }
    // Mixed control: z strained at −2 s⁻¹, x and y held at the target.
    w.periodic.targetStress.z() = 0.0;
    w.periodic.maxStrainRate.z() = 0.0;
    w.periodic.strainRate.z() = -2.0;
    double worst = 0.0;
    for (int k = 0; k < 5000; ++k) {
        sim.step();
        if (k >= 200)
            for (int a = 0; a < 2; ++a)
                worst = std::max(worst, std::abs(sim.world().periodic.stress[a] / target - 1.0));
    }
    std::printf("[ measured ] mixed control: σ_z %.4f MPa after ε_z %.3g; σ_x, σ_y within %.3g "
                "of the target\n",
                sim.world().periodic.stress.z(), -2.0 * 5000 * 2e-6, worst);
    EXPECT_LT(worst, 0.05);
    EXPECT_GT(sim.world().periodic.stress.z(), 1.5 * target);
}
