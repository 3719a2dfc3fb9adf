// The triaxial test's loading paths (TriaxialPath.h), each from one consolidated sample of about
// a hundred sand grains (as a laboratory runs each path on a like specimen): the walls do what
// the path says, measured from the walls themselves (their stresses and positions).
#include "studies/TriaxialMembrane.h"
#include "studies/TriaxialPath.h"
#include "studies/TriaxialSample.h"
#include "studies/TriaxialShearScene.h"
#include "studies/TriaxialTest.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

using namespace lsdem;

namespace {

struct Consolidated
{
    World world;
    double dt = 1.5e-6;
    TriaxialProtocol protocol;
    TriaxialTestResult result;
};

/// The bundled sand at SDP 0.15: @a grains of it on the study's lattice (seed 1), as the
/// study builds its world, between walls or in a periodic cell.
struct SandSample
{
    TriaxialOptions options;
    TriaxialAssets assets;
    World world;
};
SandSample sandSample(long long grains, bool periodic)
{
    SandSample s;
    TriaxialOptions& o = s.options;
    o.meshes = {std::string(LSDEM_SOURCE_DIR) + "/assets/meshes/sand"};
    o.sdps = {0.15};
    o.grains = grains;
    o.periodic = periodic;
    const std::vector<std::string> files = triaxialMeshFiles(o);
    s.assets = bakeTriaxialAssets(files, o.vdp, o.sdps[0]);
    const TriaxialCloud cloud =
        makeTriaxialCloud(o.grains, int(files.size()), triaxialCloudSpacing(s.assets), 1);
    std::vector<std::string> warnings;
    s.world = buildWorld(triaxialScene(o, s.assets, cloud, Formulation::Adapted, o.knStar), warnings);
    return s;
}

/// The sample of TestTriaxialTest, consolidated to 100 kPa once for every path.
const Consolidated& consolidated()
{
    static const Consolidated c = [] {
        SandSample sample = sandSample(100, false);
        const TriaxialOptions& o = sample.options;
        const TriaxialAssets& assets = sample.assets;
        Consolidated out;
        TriaxialProtocol& p = out.protocol;
        p.confiningStress = o.confiningStress;
        p.strainRate = triaxialStrainRate(o, assets.meanDiameter);
        p.consolidationRate = 10.0 * p.strainRate;
        p.maxAxialStrain = 0.02;
        p.grainDiameter = assets.meanDiameter;
        p.density = o.density;
        p.records = 100;
        Simulation sim(std::move(sample.world), out.dt);
        out.result = consolidateTriaxial(sim, triaxialWalls(), p);
        out.world = sim.world();
        return out;
    }();
    return c;
}

/// @a path (with @a adjust applied to the protocol) from the consolidated sample.
TriaxialTestResult sheared(TriaxialPath path,
                           const std::function<void(TriaxialProtocol&)>& adjust = {})
{
    const Consolidated& c = consolidated();
    TriaxialProtocol p = c.protocol;
    p.path = path;
    if (adjust) adjust(p);
    Simulation sim(World(c.world), c.dt);
    TriaxialTestResult r = c.result;
    shearTriaxial(sim, triaxialWalls(), p, r);
    return r;
}

std::vector<TriaxialRow> shearingRows(const TriaxialTestResult& r)
{
    std::vector<TriaxialRow> rows;
    for (const TriaxialRow& row : r.rows)
        if (row.stage == 1) rows.push_back(row);
    return rows;
}

double lateral(const TriaxialRow& row)
{
    return 0.5 * (row.state.stress.x() + row.state.stress.y());
}

} // namespace

TEST(TriaxialPath, NamesRoundTrip)
{
    for (TriaxialPath path : allTriaxialPaths())
        EXPECT_EQ(triaxialPathNamed(triaxialPathName(path)), path);
    EXPECT_EQ(allTriaxialPaths().size(), 7u);
    EXPECT_FALSE(triaxialPathNamed("shear").has_value());
}

// Extension: the ends open at the same rate, the sides hold σ₃ (the servo's lag, as in
// compression, within 10 %), so the axial stress falls below σ₃: q < 0, and the mobilised
// friction angle is measured from |q| as in compression.
TEST(TriaxialPath, ExtensionOpensTheEndsAndUnloadsTheAxis)
{
    const TriaxialTestResult r = sheared(TriaxialPath::Extension);
    const std::vector<TriaxialRow> rows = shearingRows(r);
    const double sigma3 = consolidated().protocol.confiningStress;
    const double rate = consolidated().protocol.strainRate;
    EXPECT_NEAR(rows.back().axialStrain, -0.02, rate * consolidated().dt + 1e-12);
    for (const TriaxialRow& row : rows) {
        if (row.axialStrain > -0.005) continue;
        EXPECT_NEAR(lateral(row), sigma3, 0.1 * sigma3) << row.step;
        EXPECT_LT(row.state.q, 0.0) << row.step;
    }
    std::printf("[ measured ] extension: q at the end %.4g MPa (σ₃ %.3g), friction angle %.3g°\n",
                rows.back().state.q, sigma3, r.peakFrictionAngle);
    EXPECT_GT(r.peakFrictionAngle, 10.0);
}

// Constant p: the sides follow σ_r = (3σ₃ − σ_a)/2, so p = (σ_a + 2σ_r)/3 stays at σ₃ while q
// grows. The servo corrects half its error per step and its target moves with σ_a, so p lags by
// what q gains in a step or two; 5 % of σ₃ holds that (drained compression's p rises by q/3, ~20 %
// here, so the bound tells the paths apart).
TEST(TriaxialPath, ConstantPKeepsTheMeanStress)
{
    const TriaxialTestResult r = sheared(TriaxialPath::ConstantP);
    const double sigma3 = consolidated().protocol.confiningStress;
    double worst = 0.0, qEnd = 0.0;
    for (const TriaxialRow& row : shearingRows(r)) {
        if (row.axialStrain < 0.002) continue;
        worst = std::max(worst, std::abs(row.state.p / sigma3 - 1.0));
        qEnd = row.state.q;
    }
    std::printf("[ measured ] constant p: |p/σ₃ − 1| at most %.3g, q at the end %.4g MPa\n", worst,
                qEnd);
    EXPECT_LT(worst, 0.05);
    EXPECT_GT(qEnd, 0.2 * sigma3);
}

// True triaxial at b = 0.5: σ₂ (the y sides) sits halfway between σ₃ (x) and σ₁ (the axis), as
// b = (σ₂ − σ₃)/(σ₁ − σ₃) measured from the walls once the deviator is worth measuring.
TEST(TriaxialPath, TrueTriaxialHoldsB)
{
    const TriaxialTestResult r = sheared(TriaxialPath::TrueTriaxial, [](TriaxialProtocol& p) { p.b = 0.5; });
    const double sigma3 = consolidated().protocol.confiningStress;
    double worst = 0.0;
    int measured = 0;
    for (const TriaxialRow& row : shearingRows(r)) {
        const Vec3& s = row.state.stress;
        if (s.z() - s.x() < 0.3 * sigma3) continue;
        worst = std::max(worst, std::abs((s.y() - s.x()) / (s.z() - s.x()) - 0.5));
        ++measured;
        EXPECT_NEAR(s.x(), sigma3, 0.1 * sigma3) << row.step;
    }
    std::printf("[ measured ] true triaxial b 0.5: |b − 0.5| at most %.3g over %d rows\n", worst,
                measured);
    EXPECT_GT(measured, 10);
    EXPECT_LT(worst, 0.1);
}

// Undrained (constant volume): the sides open as the ends close so that L_x·L_y·H stays as it
// was; the volume is the walls' positions, so it holds to the rounding of their displacements.
TEST(TriaxialPath, UndrainedKeepsTheVolume)
{
    const TriaxialTestResult r = sheared(TriaxialPath::Undrained);
    const std::vector<TriaxialRow> rows = shearingRows(r);
    for (const TriaxialRow& row : rows) EXPECT_LT(std::abs(row.volumetricStrain), 1e-9) << row.step;
    EXPECT_NEAR(rows.back().axialStrain, 0.02,
                consolidated().protocol.strainRate * consolidated().dt + 1e-12);
    // Each side opened by half the axial strain (to first order): L ∝ 1/sqrt(H).
    const TriaxialState& start = r.consolidated;
    const double expected = std::sqrt(1.0 / (1.0 - rows.back().axialStrain)) - 1.0;
    EXPECT_NEAR(rows.back().state.size.x() / start.size.x() - 1.0, expected, 1e-9);
    std::printf("[ measured ] undrained: p from %.4g to %.4g MPa, q %.4g MPa\n", rows.front().state.p,
                rows.back().state.p, rows.back().state.q);
}

// Unload–reload: loaded to half the end strain, unloaded until q falls to a tenth of its value
// there, reloaded to the end strain. The unloading's secant modulus E_ur is measured from it;
// a granular sample unloads stiffer than it first loaded (E_ur > E₅₀, as sands do).
TEST(TriaxialPath, UnloadReloadTurnsTwiceAndMeasuresItsModulus)
{
    const TriaxialTestResult r = sheared(TriaxialPath::UnloadReload);
    const std::vector<TriaxialRow> rows = shearingRows(r);
    // The reversal: the last row before the strain first falls (a row is taken at each turn).
    size_t reversal = 0;
    while (reversal + 1 < rows.size() && rows[reversal + 1].axialStrain >= rows[reversal].axialStrain)
        ++reversal;
    const double qTop = rows[reversal].state.q;
    double qLow = qTop;
    for (size_t k = reversal; k < rows.size(); ++k) qLow = std::min(qLow, rows[k].state.q);
    size_t top = 0;
    for (size_t k = 0; k < rows.size(); ++k)
        if (rows[k].axialStrain > rows[top].axialStrain) top = k;
    std::printf("[ measured ] unload-reload: q %.4g at ε %.4g, down to %.4g; E_ur %.4g, E50 %.4g "
                "MPa; end ε %.5g\n",
                qTop, rows[reversal].axialStrain, qLow, r.unloadReloadModulus, r.secantModulus50,
                rows.back().axialStrain);
    EXPECT_NEAR(rows[reversal].axialStrain, 0.01, 1e-4);
    EXPECT_EQ(top + 1, rows.size());  // the last row is the furthest
    EXPECT_NEAR(rows.back().axialStrain, 0.02, 2e-4);
    EXPECT_LT(qLow, 0.12 * qTop);  // unloaded (one step past a tenth at most)
    EXPECT_GT(r.unloadReloadModulus, r.secantModulus50);
}

// Cycles of ±A (A = 1 % here, two cycles): the axial strain reaches +A and −A twice each and
// ends back at zero, the sides holding σ₃ throughout.
TEST(TriaxialPath, CyclesReachTheAmplitudeBothWays)
{
    const TriaxialTestResult r = sheared(TriaxialPath::Cyclic, [](TriaxialProtocol& p) {
        p.maxAxialStrain = 0.01;
        p.cycles = 2;
    });
    const std::vector<TriaxialRow> rows = shearingRows(r);
    const double step = consolidated().protocol.strainRate * consolidated().dt;
    int peaks = 0, troughs = 0;
    for (size_t k = 1; k + 1 < rows.size(); ++k) {
        const double e = rows[k].axialStrain;
        if (e >= rows[k - 1].axialStrain && e >= rows[k + 1].axialStrain && e > 0.009) ++peaks;
        if (e <= rows[k - 1].axialStrain && e <= rows[k + 1].axialStrain && e < -0.009) ++troughs;
    }
    double high = -1.0, low = 1.0;
    for (const TriaxialRow& row : rows) high = std::max(high, row.axialStrain), low = std::min(low, row.axialStrain);
    std::printf("[ measured ] cycles: %d peaks, %d troughs, strain from %.5g to %.5g, end %.3g\n",
                peaks, troughs, low, high, rows.back().axialStrain);
    EXPECT_EQ(peaks, 2);
    EXPECT_EQ(troughs, 2);
    EXPECT_NEAR(high, 0.01, 2.0 * step + 1e-4);
    EXPECT_NEAR(low, -0.01, 2.0 * step + 1e-4);
    EXPECT_NEAR(rows.back().axialStrain, 0.0, 2.0 * step + 1e-6);
}

// The same test on a periodic cell (--boundary periodic): 200 grains (a cell of fewer would be
// squeezed below twice a pair's reach), no walls. The cell's stress is the contacts' Love–Weber
// stress, so the two measures agree to round-off; consolidated, each is σ₃ within the 2 %
// tolerance; compressed to 1 %, the x and y axes hold σ₃ within 10 % while q grows; undrained,
// the cell's volume holds to round-off (its axes scale by exact factors).
TEST(TriaxialPath, APeriodicCellConsolidatesCompressesAndKeepsItsVolume)
{
    const SandSample sample = sandSample(200, true);
    const World& start = sample.world;
    TriaxialProtocol p = consolidated().protocol;
    p.maxAxialStrain = 0.01;
    ASSERT_TRUE(start.boundaries.empty());
    ASSERT_GT(start.periodic.size.minCoeff(), 0.0);
    Simulation sim(World(start), 1.5e-6);
    const TriaxialTestResult base = consolidateTriaxial(sim, periodicTriaxialCell(), p);
    ASSERT_TRUE(base.consolidatedWithinTolerance);
    const TriaxialState& c = base.consolidated;
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(c.stress[a], p.confiningStress, 0.02 * p.confiningStress) << a;
        EXPECT_NEAR(c.loveWeberStress[a], c.stress[a], 1e-9 * p.confiningStress) << a;
    }
    const World consolidatedWorld = sim.world();
    for (TriaxialPath path : {TriaxialPath::Compression, TriaxialPath::Undrained}) {
        TriaxialProtocol q = p;
        q.path = path;
        Simulation run(World(consolidatedWorld), 1.5e-6);
        TriaxialTestResult r = base;
        shearTriaxial(run, periodicTriaxialCell(), q, r);
        const std::vector<TriaxialRow> rows = shearingRows(r);
        EXPECT_NEAR(rows.back().axialStrain, 0.01, 1e-4) << triaxialPathName(path);
        for (const TriaxialRow& row : rows) {
            if (path == TriaxialPath::Undrained) {
                EXPECT_LT(std::abs(row.volumetricStrain), 1e-9) << row.step;
            } else if (row.axialStrain > 0.005) {
                EXPECT_NEAR(lateral(row), p.confiningStress, 0.1 * p.confiningStress) << row.step;
                EXPECT_GT(row.state.q, 0.0) << row.step;
            }
        }
        std::printf("[ measured ] periodic %s: e0 %.3f, Z0 %.2f; at ε_a %.4f: p %.4g, q %.4g "
                    "MPa, ε_v %.3g\n",
                    triaxialPathName(path).c_str(), c.voidRatio, c.coordination,
                    rows.back().axialStrain, rows.back().state.p, rows.back().state.q,
                    rows.back().volumetricStrain);
    }
}

// A membrane round a cylinder cut from the sample consolidated between walls (TriaxialMembrane.h):
// every grain kept lies wholly inside the membrane as it is put on; consolidated again under
// the cell pressure and the platens, the grains' push on the membrane (measured from their
// contacts) and on the platens both come to σ₃, with a void ratio a sand can have (a membrane
// that wrapped each grain instead of bridging the voids between them would enclose too little:
// a membrane of the laboratory's proportion to the sample, 0.05 mm here, gave 0.14); the
// membrane's pressure is above σ₃ (a stretched membrane holds the grains in too: the
// laboratory's membrane correction, here 36 % of σ₃ on a cylinder 4 grains across, which
// steering the pressure makes up for); then drained compression to 1 % keeps the grains'
// lateral stress at σ₃ within 10 % and raises q.
TEST(TriaxialPath, AMembraneHoldsSigma3RoundACylinderCutFromTheSample)
{
    const Consolidated& c = consolidated();
    TriaxialOptions o;
    TriaxialProtocol p = c.protocol;
    p.maxAxialStrain = 0.01;
    const double kn = o.knStar;
    const TriaxialMembraneSample sample =
        wrapInMembrane(c.world, triaxialWalls(), o, p.grainDiameter, c.dt, kn, p.strainRate);
    const Membrane& m = sample.world.membranes[0];
    ASSERT_GT(sample.world.grains.size(), 20u);
    EXPECT_EQ(sample.world.grains.size() + size_t(sample.grainsCut), c.world.grains.size());
    Vec3 axis = Vec3::Zero();
    for (const Vec3& x : m.positions) axis += x;
    axis /= double(m.positions.size());
    for (const Grain& g : sample.world.grains) {
        const Vec3& x = g.body.pose.position;
        EXPECT_LE(std::hypot(x.x() - axis.x(), x.y() - axis.y()) + g.asset->boundingRadius,
                  sample.radius * (1.0 + 1e-12));
    }

    // (At the walls' step a grain pressed by the falling membrane exceeds its stable step, as in
    // the study, which then halves it: the membrane's density stays as set for c.dt.)
    Simulation sim(World(sample.world), 0.5 * c.dt);
    p.maxConsolidationSteps = 60000;  // (it settles in about 4000; failing, it would run long)
    const TriaxialTestResult base = consolidateTriaxial(sim, sample.walls, p);
    ASSERT_TRUE(base.consolidatedWithinTolerance);
    const TriaxialState& s = base.consolidated;
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(s.stress[a], p.confiningStress, 0.02 * p.confiningStress) << a;
    const double pressure = sim.world().membranes[0].pressure;
    EXPECT_GT(pressure, s.stress.x());
    EXPECT_LT(pressure, 3.0 * p.confiningStress);
    EXPECT_GT(s.voidRatio, 0.2);
    EXPECT_LT(s.voidRatio, 1.0);
    // The grains' Love–Weber stress over the membrane's volume, their contacts on the membrane
    // counted with the moment of their fanned-out point forces, is the lateral stress the
    // membrane measures (for a sample at rest the two are one sum; without that moment it was
    // 0.072 against 0.100). Axially the platens also carry the membrane's own push on its rims,
    // which the grains do not, and the two are not the same sum: on 27 grains the grains' axial
    // stress was measured at 0.082, 0.069 and 0.103 against the platens' 0.100–0.101 MPa as the
    // grains' level sets changed by less than 0.01 voxel (2026-11-30: a narrow band of lsdem's
    // own), so neither its sign nor its size is asserted beyond the packing's own spread.
    for (int a = 0; a < 2; ++a)
        EXPECT_NEAR(s.loveWeberStress[a], s.stress[a], 0.05 * p.confiningStress) << a;
    EXPECT_NEAR(s.loveWeberStress.z(), s.stress.z(), 0.4 * p.confiningStress);
    std::printf("[ measured ] membrane sample's Love-Weber stress %.4g %.4g %.4g against the "
                "boundaries' %.4g %.4g %.4g MPa\n",
                s.loveWeberStress.x(), s.loveWeberStress.y(), s.loveWeberStress.z(), s.stress.x(),
                s.stress.y(), s.stress.z());

    const World consolidatedWorld = sim.world();
    TriaxialTestResult r = base;
    shearTriaxial(sim, sample.walls, p, r);
    const std::vector<TriaxialRow> rows = shearingRows(r);
    EXPECT_NEAR(rows.back().axialStrain, 0.01, 1e-4);
    for (const TriaxialRow& row : rows)
        if (row.axialStrain > 0.005) {
            EXPECT_NEAR(lateral(row), p.confiningStress, 0.1 * p.confiningStress) << row.step;
            EXPECT_GT(row.state.q, 0.0) << row.step;
        }
    std::printf("[ measured ] membrane: %zu grains (%lld cut), radius %.3g mm, its mass %.3g "
                "times theirs; consolidated e %.3f, pressure %.4g for sigma_r %.4g MPa; at "
                "eps_a %.4f: q %.4g MPa, eps_v %.3g\n",
                sample.world.grains.size(), sample.grainsCut, sample.radius, sample.massRatio,
                s.voidRatio, pressure, s.stress.x(), rows.back().axialStrain,
                rows.back().state.q, rows.back().volumetricStrain);

    // Undrained from the same consolidated sample: the pressure servoed on the enclosed volume
    // keeps it (the drained run above changed it far more), and the grains' lateral stress
    // moves the way the drained volume tried to: a sample that contracted drained loses
    // effective stress undrained (its pore pressure rises), one that dilated gains.
    Simulation undrainedSim(World(consolidatedWorld), sim.timeStep());
    TriaxialProtocol u = p;
    u.path = TriaxialPath::Undrained;
    TriaxialTestResult ur = base;
    shearTriaxial(undrainedSim, sample.walls, u, ur);
    const std::vector<TriaxialRow> undrained = shearingRows(ur);
    const double drainedChange = rows.back().volumetricStrain;
    double worst = 0.0;
    for (const TriaxialRow& row : undrained) worst = std::max(worst, std::abs(row.volumetricStrain));
    EXPECT_LT(worst, 0.25 * std::abs(drainedChange));
    const double effectiveChange = lateral(undrained.back()) - p.confiningStress;
    EXPECT_GT(std::abs(effectiveChange), 0.05 * p.confiningStress);
    EXPECT_EQ(effectiveChange < 0.0, drainedChange > 0.0);
    EXPECT_GT(undrained.back().state.q, 0.0);
    std::printf("[ measured ] undrained membrane: |eps_v| at most %.3g (drained %.3g); at eps_a "
                "%.4f sigma_r %.4g MPa, q %.4g MPa\n",
                worst, drainedChange, undrained.back().axialStrain, lateral(undrained.back()),
                undrained.back().state.q);
}
