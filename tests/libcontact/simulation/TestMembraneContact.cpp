// Grains against a membrane in a running simulation (MembraneContact.h, SimulationMembranes):
// a membrane held flat is a wall (the same force as a plane boundary), an impact on a free
// tube conserves momentum to round-off and energy to the integrator's order, and the result
// is the same on any thread count. Units: mm, N, s, tonne.
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"
#include "lsdem/simulation/StableStep.h"
#include "lsdem/ls/Bake.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <iostream>
#include <memory>

using namespace lsdem;

namespace {

std::shared_ptr<const GrainAsset> sphere()
{
    static const auto asset = [] {
        BakeOptions o;
        o.voxelSize = 0.25;
        o.nodePlacement = NodePlacement::Count;
        o.nodeCount = 2000;
        std::vector<std::string> warnings;
        return std::make_shared<const GrainAsset>(
            bakeAnalytic(AnalyticShape::sphere(5.0), o, warnings));
    }();
    return asset;
}

MembraneMaterial latex()
{
    MembraneMaterial r;
    r.youngs = 1.4;
    r.poisson = 0.45;
    r.thickness = 0.3;
    r.density = 1e-6;  // a thousand times rubber's: mass scaling, as a quasi-static test uses
    return r;
}

/// One steel sphere (R 5) at @a position moving at @a velocity, adapted law (kn* 1e3, no
/// dashpot, no friction), and a plane z = @a floorHeight (normal +z).
World oneSphere(const Vec3& position, const Vec3& velocity, double floorHeight)
{
    Scene s;
    AssetSpec a;
    a.name = "sphere";
    a.loaded = sphere();
    a.where = "TestMembraneContact";
    s.assets.push_back(a);
    MaterialSpec steel;
    steel.name = "steel";
    steel.density = 7.85e-9;
    s.materials.push_back(steel);
    ContactSpec c;
    c.model.formulation = Formulation::Adapted;
    c.model.normalStiffness = 1e3;
    c.model.damping = ViscousDamping(1.0);
    s.contacts.push_back(c);
    GrainSpec g;
    g.pose.position = position;
    g.velocity = velocity;
    s.grains.push_back(g);
    BoundarySpec b;
    b.name = "floor";
    b.shape = BoundaryShape::Plane;
    b.point = Vec3(0, 0, floorHeight);
    b.normal = Vec3::UnitZ();
    s.boundaries.push_back(b);
    std::vector<std::string> warnings;
    return buildWorld(s, warnings);
}

/// A square sheet in the plane z = 0, 20 × 20 mm in 2 mm squares, facing −z (grains above
/// it press down), every vertex held by boundary 0.
Membrane heldSheet()
{
    Membrane m;
    m.name = "sheet";
    m.rubber = latex();
    const int n = 11;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) m.positions.emplace_back(-10.0 + 2 * i, -10.0 + 2 * j, 0.0);
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
            MembraneTriangle t1, t2;
            t1.vertices = {a, c, b};  // clockwise seen from +z: the normal is −z
            t2.vertices = {a, d, c};
            m.triangles.push_back(t1);
            m.triangles.push_back(t2);
        }
    finishMembrane(m);
    m.heldBy.assign(m.positions.size(), 0);
    return m;
}

/// The impact's step: ω·dt ≈ 0.05 for the stiffest contact the sphere makes with the tube.
constexpr double kImpactStep = 2e-6;

Vec3 momentum(const World& w)
{
    Vec3 p = Vec3::Zero();
    for (const Grain& g : w.grains) p += g.body.mass * g.body.velocity;
    for (const Membrane& m : w.membranes)
        for (size_t i = 0; i < m.positions.size(); ++i) p += m.masses[i] * m.velocities[i];
    return p;
}

/// A steel sphere flying at 200 mm/s into the side of a free latex tube (R 20, 40 long), no
/// gravity, no pressure; it starts 0.04 mm clear of the facet it flies at (the facets lie
/// 0.06 mm inside R).
World sphereIntoTube()
{
    World w = oneSphere(Vec3(14.9, 0.3, 1.1), Vec3(200.0, 0, 0), -1000.0);
    Membrane tube = makeTubeMembrane(Vec3(0, 0, -20), Vec3::UnitZ(), 20.0, 40.0, 40, 10, latex());
    tube.name = "tube";
    w.membranes.push_back(tube);
    return w;
}

} // namespace

// A membrane whose every vertex is held still is a rigid wall: a sphere pressed 0.1 mm into
// a held flat sheet feels the force (and no torque) that it feels from a plane boundary at
// the same place, to round-off (the depth is measured from the triangle's plane there, from
// the plane's point here); the sheet takes the opposite force.
TEST(MembraneContact, HeldFlatSheetPushesAsAWall)
{
    World walled = oneSphere(Vec3(0.3, -0.2, 4.9), Vec3::Zero(), 0.0);
    World sheeted = oneSphere(Vec3(0.3, -0.2, 4.9), Vec3::Zero(), -1000.0);
    sheeted.membranes.push_back(heldSheet());
    const Simulation wall(std::move(walled), 1e-7);
    const Simulation sheet(std::move(sheeted), 1e-7);
    const Grain& onWall = wall.world().grains[0];
    const Grain& onSheet = sheet.world().grains[0];
    ASSERT_GT(onWall.force.z(), 0.0);
    std::cout << "[ measured ] sphere on a wall " << onWall.force.transpose()
              << " N, on a held sheet " << onSheet.force.transpose() << " N\n";
    EXPECT_LT((onSheet.force - onWall.force).norm(), 1e-9 * onWall.force.norm());
    EXPECT_LT((onSheet.torque - onWall.torque).norm(), 1e-9 * onWall.force.norm() * 5.0);
    EXPECT_EQ(sheet.contactNodes(), wall.contactNodes());
    Vec3 reaction = Vec3::Zero();
    for (const Vec3& f : sheet.world().membranes[0].forces) reaction += f;
    EXPECT_LT((reaction + onSheet.force).norm(), 1e-12 * onWall.force.norm());
}

// A sphere flying into a free tube: grain and membrane exchange equal and opposite forces
// (each node's reaction split over its triangle's vertices by weights summing to 1), and the
// rubber's forces sum to zero, so velocity Verlet keeps the total momentum to round-off. No
// dashpot, friction or damping: the energy (kinetic of both, the rubber's and the contact's
// elastic) is kept to O((ω·dt)²); the step is a fifth of the stable one, and the run must
// carry at least a tenth of the energy into the membrane for the check to mean anything.
TEST(MembraneContact, ImpactOnAFreeTubeConservesMomentumAndEnergy)
{
    World w = sphereIntoTube();
    const double dt = kImpactStep;
    Simulation run(std::move(w), dt);
    const Vec3 p0 = momentum(run.world());
    const Energies e0 = run.energies();
    const double total0 = e0.kinetic + e0.elastic;
    double membraneShare = 0.0, worstEnergy = 0.0, worstMomentum = 0.0;
    int steps = 0;
    while (steps < 40000 && (steps < 100 || run.world().grains[0].body.velocity.x() > 0.0)) {
        run.step();
        ++steps;
        const Energies e = run.energies();
        const double grainKinetic = run.world().grains[0].body.kineticEnergy();
        membraneShare = std::max(membraneShare, 1.0 - grainKinetic / total0);
        worstEnergy = std::max(worstEnergy, std::abs(e.kinetic + e.elastic - total0) / total0);
        worstMomentum = std::max(worstMomentum, (momentum(run.world()) - p0).norm() / p0.norm());
    }
    std::cout << "[ measured ] sphere into a free tube, " << steps << " steps of " << dt
              << " s: rebound vx " << run.world().grains[0].body.velocity.x()
              << " mm/s, most energy away from the sphere " << membraneShare
              << ", worst energy drift " << worstEnergy << ", worst momentum drift "
              << worstMomentum << "\n";
    EXPECT_GT(membraneShare, 0.1);
    EXPECT_LT(worstMomentum, 1e-12);
    EXPECT_LT(worstEnergy, 2e-3);
    EXPECT_EQ(run.energies().boundaryWork, 0.0);
}

// The same impact on one thread and on two: the same bytes.
TEST(MembraneContact, SameNumbersOnAnyThreadCount)
{
    auto runOn = [](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        Simulation run(sphereIntoTube(), kImpactStep);
        for (int s = 0; s < 400; ++s) run.step();
        return run.world();
    };
    const World one = runOn(1), two = runOn(2);
    EXPECT_EQ(one.grains[0].body.pose.position, two.grains[0].body.pose.position);
    EXPECT_EQ(one.grains[0].body.velocity, two.grains[0].body.velocity);
    EXPECT_EQ(one.membranes[0].positions, two.membranes[0].positions);
    EXPECT_LT(one.grains[0].body.velocity.x(), 199.0);  // it has met the tube
}
