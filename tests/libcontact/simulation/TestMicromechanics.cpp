// Micromechanics (Micromechanics.h) on lattices of balls pressed between six walls, against
// closed forms: the fabric of a cubic lattice is I/3 (anisotropy 0) and of a square layer
// diag(1/2, 1/2, 0) (anisotropy 15/4); each ball of a 2×2×2 lattice touches three others
// (coordination 3) and a lone ball is a rattler; and the Love–Weber stress moment obeys the
// virial identity Σ_p M_p + Σ_p x_p ⊗ F_p = Σ over wall contacts of x_c ⊗ f_c (F_p the ball's
// net force as the simulation summed it), so in equilibrium it is the walls' force times the
// distance between them; and the branch vectors' and the normal forces' fabrics of contacts
// made by hand against their closed forms.
#include "lsdem/simulation/Micromechanics.h"

#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace lsdem;

namespace {

constexpr double kRadius = 1.0, kOverlap = 0.04;

/// Balls of radius 1 at (±a, ±a, ±a) (a layer at z = 0 if @a layers is 1), overlapping each
/// neighbour by kOverlap and the walls around them by kOverlap/√2, which presses a ball on a
/// wall as hard as two balls together (the adapted law on a ball: π·kn*·R_eff·δ², R_eff = R
/// on a wall and R/2 between balls). @a loneBall adds a ball beyond the lattice on +x, touching
/// nothing (the +x wall moved away for it).
World lattice(int layers, bool loneBall)
{
    const double a = kRadius - kOverlap / 2;  // neighbours 2a apart
    const double onWall = kOverlap / std::sqrt(2.0);
    const double wall = a + kRadius - onWall;
    std::ostringstream s;
    s << "[assets.ball]\nshape = \"sphere\"\nradius = 1.0\nvoxel = 0.05\nnodes = 2000\n\n"
         "[materials.glass]\ndensity = 2.5e-9\n\n[[contacts]]\nmaterials = [\"glass\", \"glass\"]\n"
         "normal_stiffness = 1e3\n\n";
    for (int i = 0; i < 8; ++i) {
        if (layers == 1 && (i & 4)) continue;
        const double z = layers == 1 ? 0.0 : ((i & 4) ? a : -a);
        s << "[[grains]]\nasset = \"ball\"\nmaterial = \"glass\"\nposition = [" << ((i & 1) ? a : -a)
          << ", " << ((i & 2) ? a : -a) << ", " << z << "]\n\n";
    }
    const double lone = a + 2.0 * kRadius + 0.5;
    if (loneBall)
        s << "[[grains]]\nasset = \"ball\"\nmaterial = \"glass\"\nposition = [" << lone << ", 0, 0]\n\n";
    const double zWall = layers == 1 ? kRadius - onWall : wall;
    const char* names[] = {"x0", "x1", "y0", "y1", "z0", "z1"};
    for (int w = 0; w < 6; ++w) {
        const int axis = w / 2;
        const double sign = (w % 2) ? 1.0 : -1.0;
        Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
        point[axis] = sign * (axis == 2 ? zWall : wall);
        if (loneBall && w == 1) point[axis] = lone + kRadius + 0.5;
        normal[axis] = -sign;
        s << "[[boundaries]]\nname = \"" << names[w] << "\"\ntype = \"plane\"\nmaterial = \"glass\"\n"
          << "point = [" << point.x() << ", " << point.y() << ", " << point.z() << "]\n"
          << "normal = [" << normal.x() << ", " << normal.y() << ", " << normal.z() << "]\n\n";
    }
    s << "[simulation]\nend_steps = 1\n";
    std::vector<std::string> warnings;
    return buildWorld(parseScene(s.str(), "lattice.toml"), warnings);
}

/// The largest angle between a grain contact's normal and the line of the two balls' centres.
double largestTilt(const World& w, const std::vector<ContactRecord>& records)
{
    double tilt = 0.0;
    for (const ContactRecord& r : records) {
        if (r.second < 0) continue;
        const Vec3 branch = (w.grains[size_t(r.first)].body.pose.position -
                             w.grains[size_t(r.second)].body.pose.position).normalized();
        tilt = std::max(tilt, std::acos(std::min(1.0, r.normal.dot(branch))));
    }
    return tilt;
}

} // namespace

TEST(Micromechanics, CubicLatticeIsIsotropicWithThreeContactsABallAndALoneRattler)
{
    Simulation sim(lattice(2, true), 1e-7);
    const std::vector<ContactRecord> records = sim.contactRecords();
    const Micromechanics m = micromechanicsOf(sim.world(), records);
    EXPECT_EQ(m.grainContacts, 12);
    EXPECT_EQ(m.boundaryContacts, 20);  // the +x wall stands back
    EXPECT_EQ(m.freeGrains, 9);
    EXPECT_EQ(m.rattlers, 1);
    EXPECT_DOUBLE_EQ(m.mechanicalCoordination, 3.0);  // (2·12 − 0)/(9 − 1)
    // A normal tilted by θ from its axis moves n ⊗ n by at most 2θ (entry by entry); the
    // contacts' node patterns tilt them a little (their caps span about 0.2 rad).
    const double tilt = largestTilt(sim.world(), records);
    EXPECT_LT(tilt, 0.1);
    EXPECT_LE((m.fabric - Mat3::Identity() / 3.0).cwiseAbs().maxCoeff(), 2.0 * tilt);
    EXPECT_NEAR(m.fabric.trace(), 1.0, 1e-12);
    EXPECT_LE(m.fabricAnisotropy, 7.5 * std::sqrt(1.5) * 3.0 * 2.0 * tilt);
}

TEST(Micromechanics, SquareLayerHasTheFabricOfAPlane)
{
    Simulation sim(lattice(1, false), 1e-7);
    const std::vector<ContactRecord> records = sim.contactRecords();
    const Micromechanics m = micromechanicsOf(sim.world(), records);
    EXPECT_EQ(m.grainContacts, 4);
    EXPECT_DOUBLE_EQ(m.mechanicalCoordination, 2.0);
    const double tilt = largestTilt(sim.world(), records);
    const Mat3 planar = Vec3(0.5, 0.5, 0.0).asDiagonal();
    EXPECT_LE((m.fabric - planar).cwiseAbs().maxCoeff(), 2.0 * tilt);
    // a = 15/2·(diag(1/2, 1/2, 0) − I/3) = diag(5/4, 5/4, −5/2): sqrt(3/2·a:a) = 15/4.
    EXPECT_NEAR(m.fabricAnisotropy, 3.75, 7.5 * std::sqrt(1.5) * 3.0 * 2.0 * tilt);
}

TEST(Micromechanics, StressMomentObeysTheVirialIdentityAndMatchesTheWalls)
{
    Simulation sim(lattice(2, false), 1e-7);
    const World& w = sim.world();
    const std::vector<ContactRecord> records = sim.contactRecords();
    const Micromechanics m = micromechanicsOf(w, records);
    // Σ_p M_p + Σ_p x_p ⊗ F_p = Σ over wall contacts of x_c ⊗ f_c (the grain pairs' terms
    // cancel: both balls feel their contact at one point). F_p and the wall contacts come from
    // the simulation's own sums, not from the micromechanics.
    Mat3 left = m.stressMoment, right = Mat3::Zero();
    double scale = 0.0;
    for (const Grain& g : w.grains) left += g.body.pose.position * g.force.transpose();
    for (const ContactRecord& r : records) {
        if (r.boundary >= 0) right += r.centre * r.force.transpose();
        scale = std::max(scale, r.force.norm());
    }
    EXPECT_LE((left - right).cwiseAbs().maxCoeff(), 1e-12 * scale * 4.0);
    // Each wall's reaction is the opposite of its contacts' forces on the balls.
    for (size_t b = 0; b < w.boundaries.size(); ++b) {
        Vec3 onBalls = Vec3::Zero();
        for (const ContactRecord& r : records)
            if (r.boundary == int(b)) onBalls += r.force;
        EXPECT_LE((w.boundaries[b].force + onBalls).norm(), 1e-12 * scale * 8.0) << b;
    }
    // Near equilibrium (the node patterns leave each ball a small net force F_p), the zz moment
    // is the top wall's force times the gap between the walls: the contact centres lie within
    // the overlap of the walls, and Σ x_p ⊗ F_p is what the imbalance adds.
    const double gap = w.boundaries[5].plane.point.z() - w.boundaries[4].plane.point.z();
    const double top = std::abs(w.boundaries[5].force.z());
    double imbalance = 0.0;
    for (const Grain& g : w.grains) imbalance += g.body.pose.position.norm() * g.force.norm();
    // (The two contacts' node sums differ from the continuum's π·kn*·R_eff·δ² by a few % each.)
    EXPECT_LT(imbalance, 0.1 * top * gap);
    EXPECT_NEAR(m.stressMoment(2, 2), -top * gap, top * kOverlap + imbalance);
    EXPECT_NEAR(m.stressMoment(0, 0), m.stressMoment(2, 2), 2.0 * (top * kOverlap + imbalance));
    // And each ball's own stress averages to the sample's: Σ V_p σ_p = Σ_p M_p.
    const std::vector<Mat3> perGrain = grainStresses(w, records);
    Mat3 summed = Mat3::Zero();
    for (size_t p = 0; p < w.grains.size(); ++p) summed += w.grains[p].asset->mass.volume * perGrain[p];
    EXPECT_LE((summed - m.stressMoment).cwiseAbs().maxCoeff(), 1e-12 * scale * 8.0);
}

// The branch vectors' and the forces' fabrics, on contacts made by hand: grain 0 at the
// origin touches grain 1 above it (normal and branch along z, normal force 2) and grain 2 at
// (1, 0, 1) along x (a normal along x, as an elongated grain's side would give, with its
// branch at 45°; normal force 1, and a tangential part that does not count). Then
// branch fabric = ½·e_z e_z + ½·l̂ l̂ with l̂ = (1, 0, 1)/√2, that is [[¼, 0, ¼], [0, 0, 0],
// [¼, 0, ¾]]; force fabric = (2·e_z e_z + 1·e_x e_x)/3 = diag(⅓, 0, ⅔); mean normal force 3/2;
// each anisotropy sqrt(3/2·a:a) of a = 15/2·(F − I/3), worked out here by hand.
TEST(Micromechanics, BranchAndForceFabricsOfContactsMadeByHand)
{
    World w;
    for (const Vec3& x : {Vec3(0, 0, 0), Vec3(0, 0, 2), Vec3(1, 0, 1)}) {
        Grain g;
        g.body.pose.position = x;
        w.grains.push_back(g);
    }
    ContactRecord up, side;
    up.first = 0, up.second = 1, up.normal = Vec3(0, 0, -1), up.force = Vec3(0, 0, -2);
    side.first = 2, side.second = 0, side.normal = Vec3(1, 0, 0), side.force = Vec3(1, 0, 0.3);
    const Micromechanics m = micromechanicsOf(w, {up, side});
    ASSERT_EQ(m.grainContacts, 2);
    Mat3 branch;
    branch << 0.25, 0, 0.25, 0, 0, 0, 0.25, 0, 0.75;
    EXPECT_LT((m.branchFabric - branch).norm(), 1e-15);
    const Mat3 force = Vec3(1.0 / 3, 0, 2.0 / 3).asDiagonal();
    EXPECT_LT((m.forceFabric - force).norm(), 1e-15);
    EXPECT_DOUBLE_EQ(m.meanNormalForce, 1.5);
    // a = 15/2·(F − I/3). Force: diag(0, −5/2, 5/2), a:a = 25/2, sqrt(3/2·25/2) = 5·√3/2.
    EXPECT_NEAR(m.forceAnisotropy, 2.5 * std::sqrt(3.0), 1e-13);
    // Branch: 15/2·diag(−1/12, −1/3, 5/12) and 15/8 off the diagonal (twice):
    // a:a = (225/4)·(1/144 + 1/9 + 25/144) + 2·(15/8)² = 225/4·(42/144) + 225/32.
    const double aa = 225.0 / 4.0 * 42.0 / 144.0 + 225.0 / 32.0;
    EXPECT_NEAR(m.branchAnisotropy, std::sqrt(1.5 * aa), 1e-13);
    // The normals' own fabric: diag(½, 0, ½), anisotropy 15/4.
    EXPECT_NEAR(m.fabricAnisotropy, 3.75, 1e-13);
}
