// What a triaxial test reads off its cell (tools/studies/TriaxialCell): sizes from the walls'
// positions, principal stresses from their forces over the current areas, p, q, strains, void
// ratio, coordination and the mobilised friction angle, against values worked out by hand.
#include "studies/TriaxialCell.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace lsdem;

namespace {

Boundary plane(const std::string& name, const Vec3& point, const Vec3& normal)
{
    Boundary b;
    b.name = name;
    b.shape = BoundaryShape::Plane;
    b.plane.point = point;
    b.plane.normal = normal;
    return b;
}

/// The cell [0, 2] × [0, 3] × [0, 4] with walls 0 … 5 in the order x min, x max, y min, ...
World boxCell()
{
    World w;
    w.boundaries = {plane("west", Vec3(0, 0, 0), Vec3::UnitX()),
                    plane("east", Vec3(2, 0, 0), -Vec3::UnitX()),
                    plane("south", Vec3(0, 0, 0), Vec3::UnitY()),
                    plane("north", Vec3(0, 3, 0), -Vec3::UnitY()),
                    plane("bottom", Vec3(0, 0, 0), Vec3::UnitZ()),
                    plane("top", Vec3(0, 0, 4), -Vec3::UnitZ())};
    return w;
}

TriaxialWalls walls()
{
    TriaxialWalls t;
    t.index = {0, 1, 2, 3, 4, 5};
    return t;
}

} // namespace

TEST(TriaxialCell, StressesStrainsAndVoidRatioFromTheWalls)
{
    World w = boxCell();
    const TriaxialState start = measureTriaxialCell(w, walls(), {});
    EXPECT_EQ(start.size, Vec3(2, 3, 4));
    EXPECT_DOUBLE_EQ(start.volume, 24.0);

    // The top comes down by 0.4 and the east wall moves out by 0.1: 2.1 × 3 × 3.6.
    w.boundaries[5].displacement = Vec3(0, 0, -0.4);
    w.boundaries[1].displacement = Vec3(0.1, 0, 0);
    // Grains push each wall outwards (against its normal). Areas: x walls 3 × 3.6 = 10.8,
    // y walls 2.1 × 3.6 = 7.56, z walls 2.1 × 3 = 6.3.
    w.boundaries[0].force = Vec3(-10.8, 0, 0);   // 1.0
    w.boundaries[1].force = Vec3(3 * 10.8, 0, 0);  // 3.0: σ_x = 2
    w.boundaries[2].force = Vec3(0, -2 * 7.56, 0);
    w.boundaries[3].force = Vec3(0, 2 * 7.56, 0);  // σ_y = 2
    w.boundaries[4].force = Vec3(0, 0, -5 * 6.3);
    w.boundaries[5].force = Vec3(0.5, 0, 5 * 6.3);  // σ_z = 5 (a tangential part is ignored)
    auto grainOfVolume = [](double v) {
        auto asset = std::make_shared<GrainAsset>();
        asset->mass.volume = v;
        Grain g;
        g.asset = asset;
        return g;
    };
    w.grains = {grainOfVolume(6.0), grainOfVolume(9.12)};  // solid 15.12 of 22.68
    w.grains[1].body.pose.position = Vec3(0, 0, 1);
    // Two contacts between the grains, each pressing them apart along z with force 2 at
    // their midpoint, of 4 and 6 nodes.
    std::vector<ContactRecord> contacts(2);
    for (ContactRecord& c : contacts) {
        c.first = 0;
        c.second = 1;
        c.force = Vec3(0, 0, -2);
        c.centre = Vec3(0, 0, 0.5);
        c.normal = Vec3(0, 0, -1);
    }
    contacts[0].nodes = 4;
    contacts[1].nodes = 6;
    const TriaxialState now = measureTriaxialCell(w, walls(), contacts);

    EXPECT_NEAR(now.size.x(), 2.1, 1e-12);
    EXPECT_NEAR(now.size.z(), 3.6, 1e-12);
    EXPECT_NEAR(now.volume, 22.68, 1e-12);
    EXPECT_NEAR(now.stress.x(), 2.0, 1e-12);
    EXPECT_NEAR(now.stress.y(), 2.0, 1e-12);
    EXPECT_NEAR(now.stress.z(), 5.0, 1e-12);
    EXPECT_NEAR(now.p, 3.0, 1e-12);
    EXPECT_NEAR(now.q, 3.0, 1e-12);
    EXPECT_NEAR(now.voidRatio, 0.5, 1e-12);        // 22.68 / 15.12 − 1
    EXPECT_DOUBLE_EQ(now.coordination, 2.0);       // 2·2 contacts / 2 grains
    EXPECT_DOUBLE_EQ(now.mechanicalCoordination, 2.0);
    EXPECT_DOUBLE_EQ(now.nodesPerContact, 5.0);
    // Each contact: (0.5·e_z)⊗(−2 e_z) on one grain and (−0.5·e_z)⊗(2 e_z) on the other, −2
    // in all along zz; two contacts, over the volume, compression positive: 4/22.68.
    EXPECT_NEAR(now.loveWeberStress.z(), 4.0 / 22.68, 1e-12);
    EXPECT_EQ(now.loveWeberStress.x(), 0.0);
    // Every normal along z: fabric e_z e_z, a = 15/2·diag(−1/3, −1/3, 2/3), sqrt(3/2 a:a) = 7.5.
    EXPECT_NEAR(now.fabricAnisotropy, 7.5, 1e-12);
    EXPECT_NEAR(axialStrain(start, now), 0.1, 1e-12);
    EXPECT_NEAR(volumetricStrain(start, now), (24.0 - 22.68) / 24.0, 1e-12);
    // sin φ = (5 − 2)/(5 + 2); and q/p = 6 sin φ / (3 − sin φ) for triaxial compression.
    const double phi = mobilisedFrictionAngle(now);
    EXPECT_NEAR(phi, std::asin(3.0 / 7.0) * 180.0 / kPi, 1e-12);
    const double sinPhi = std::sin(phi * kPi / 180.0);
    EXPECT_NEAR(now.q / now.p, 6 * sinPhi / (3 - sinPhi), 1e-12);
}

TEST(TriaxialCell, RefusesWallsThatDoNotBoundACuboid)
{
    World w = boxCell();
    TriaxialWalls swapped = walls();
    swapped.index = {1, 0, 2, 3, 4, 5};  // x max given as x min: its normal points along −x
    EXPECT_THROW(measureTriaxialCell(w, swapped, {}), Error);
    TriaxialWalls missing = walls();
    missing.index[4] = 9;
    EXPECT_THROW(measureTriaxialCell(w, missing, {}), Error);
    w.boundaries[5].shape = BoundaryShape::Sphere;
    try {
        measureTriaxialCell(w, walls(), {});
        FAIL() << "a sphere taken for a wall";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("top"), std::string::npos) << e.what();
    }
}

// A sample in a membrane (a tube of 24 facets, R 2, between platens 5 apart): its volume is the
// faceted prism's; σ_z the platens' force over volume / height; σ_r the grains' radial push on
// the membrane's vertices over 2π·R·H of the mean cylinder (R from the volume), here a push of
// 0.3 N on each of its 24 × 6 vertices, so 43.2 N in all; before any push is recorded, the
// membrane's pressure.
TEST(TriaxialCell, AMembraneSampleReadsItsVolumeAndTheGrainsPush)
{
    World w;
    w.boundaries = {plane("bottom", Vec3(1, -1, 0), Vec3::UnitZ()),
                    plane("top", Vec3(1, -1, 5), -Vec3::UnitZ())};
    MembraneMaterial rubber;
    rubber.youngs = 1.4;
    rubber.poisson = 0.45;
    rubber.thickness = 0.1;
    rubber.density = 1e-6;
    const int segments = 24, rings = 5;
    w.membranes = {makeTubeMembrane(Vec3(1, -1, 0), Vec3::UnitZ(), 2.0, 5.0, segments, rings, rubber)};
    w.membranes[0].pressure = 0.2;
    w.boundaries[0].force = Vec3(0, 0, -1.5);  // the grains push each platen out by 1.5 N
    w.boundaries[1].force = Vec3(0, 0, 1.5);
    TriaxialWalls t;
    t.index = {-1, -1, -1, -1, 0, 1};
    t.membrane = 0;

    const double volume = 0.5 * segments * 4.0 * std::sin(2.0 * kPi / segments) * 5.0;
    TriaxialState s = measureTriaxialCell(w, t, {});
    EXPECT_NEAR(s.volume / volume, 1.0, 1e-12);
    EXPECT_NEAR(s.size.z(), 5.0, 1e-12);
    EXPECT_NEAR(s.stress.z(), 1.5 / (volume / 5.0), 1e-12);
    EXPECT_EQ(s.stress.x(), 0.2);  // no push recorded: the pressure
    EXPECT_NEAR(membraneSampleArea(w, t), volume / 5.0, 1e-12);

    Membrane& m = w.membranes[0];
    m.grainForces.assign(m.positions.size(), Vec3::Zero());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const Vec3 out(m.positions[i].x() - 1.0, m.positions[i].y() + 1.0, 0.0);
        m.grainForces[i] = 0.3 * out.normalized() + Vec3(0, 0, 0.7);  // (the axial part is not lateral)
    }
    s = measureTriaxialCell(w, t, {});
    const double radius = std::sqrt(volume / (kPi * 5.0));
    const double lateral = 0.3 * segments * (rings + 1) / (2.0 * kPi * radius * 5.0);
    EXPECT_NEAR(s.stress.x(), lateral, 1e-12);
    EXPECT_NEAR(s.stress.y(), lateral, 1e-12);
    EXPECT_NEAR(s.q, s.stress.z() - lateral, 1e-12);
}
