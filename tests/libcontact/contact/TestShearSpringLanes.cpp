// The shear springs computed several contacts at a time: each lane must give exactly the bits of
// the scalar spring (updateShearForce), whether its batch is full or part-filled (the first
// kShearLanesLeast lanes at once and the rest lane by lane, or all lane by lane), and
// of a material point's velocity (ContactGrain::pointVelocity), whatever the other lanes hold,
// in every regime the spring has: sticking, sliding (Coulomb's cap), no limit (zero or
// negative), no stored force, and a stored force along the normal (nothing left on the tangent
// plane).
#include "lsdem/contact/ContactLaw.h"
#include "lsdem/contact/ShearSpringLanes.h"
#include "lsdem/contact/TangentialModel.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

using namespace lsdem;

namespace {

/// Whether two doubles are the same bits (so that 0 and −0, or two NaNs, are told apart).
bool sameBits(double a, double b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

struct SpringCase
{
    Vec3 stored, normal, slip;
    double stiffness, limit;
};

/// Random springs of every regime: the stored force and slip sized so that about half the
/// lanes stick and half slide, with the special cases mixed in.
std::vector<SpringCase> springCases(int count, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), scale(0.1, 10.0);
    std::vector<SpringCase> cases;
    for (int i = 0; i < count; ++i) {
        SpringCase c;
        c.normal = Vec3(unit(random), unit(random), unit(random)).normalized();
        c.stored = scale(random) * Vec3(unit(random), unit(random), unit(random));
        c.slip = 1e-3 * scale(random) * Vec3(unit(random), unit(random), unit(random));
        c.stiffness = 100.0 * scale(random);
        c.limit = 1.5 * scale(random);
        if ((i / 8) % 5 == 4) {
            // Every fifth run of eight: a far cap, so that a whole batch sticks and the
            // spring's vector path without Coulomb's cap is taken too.
            c.limit = 1e9;
            cases.push_back(c);
            continue;
        }
        switch (i % 8) {
        case 1: c.limit = 0.0; break;                     // no normal force: no shear
        case 2: c.limit = -1.0; break;                    // a pulling node: no shear either
        case 3: c.stored = Vec3::Zero(); break;           // a node just entering contact
        case 4: c.stored = 2.0 * c.normal; break;         // nothing on the tangent plane
        case 5: c.slip = Vec3::Zero(); c.limit = 1e9; break;  // only turned
        default: break;
        }
        cases.push_back(c);
    }
    return cases;
}

} // namespace

TEST(ShearSpringLanes, SameBitsAsUpdateShearForce)
{
    const std::vector<SpringCase> cases = springCases(4000, 7);
    const Vec3 meanTurn(2e-3, -1e-3, 3e-3);
    int sliding = 0, sticking = 0;
    for (size_t first = 0; first < cases.size(); first += kShearLanes) {
        // Every fourth batch is filled partly, as a side's last batch may be, with 1 to
        // kShearLanes - 1 lanes in turn: below kShearLanesLeast lane by lane, from it that many
        // lanes at once and the rest lane by lane.
        const size_t batch = first / kShearLanes;
        const int used = batch % 4 == 3 ? 1 + static_cast<int>((batch / 4) % (kShearLanes - 1))
                                        : kShearLanes;
        ShearSpringLanes lanes;
        for (int l = 0; l < used; ++l) {
            const SpringCase& c = cases[first + static_cast<size_t>(l)];
            lanes.nx[l] = c.normal.x();
            lanes.ny[l] = c.normal.y();
            lanes.nz[l] = c.normal.z();
            lanes.ux[l] = c.slip.x();
            lanes.uy[l] = c.slip.y();
            lanes.uz[l] = c.slip.z();
            lanes.sx[l] = c.stored.x();
            lanes.sy[l] = c.stored.y();
            lanes.sz[l] = c.stored.z();
            lanes.stiffness[l] = c.stiffness;
            lanes.limit[l] = c.limit;
        }
        // A part-filled batch as the law computes it; and, for comparison, all lanes at once
        // with whatever the unused lanes hold (the results of the lanes in use must not depend
        // on them).
        ShearSpringLanes whole = lanes;
        if (used == kShearLanes) {
            lanes.update(meanTurn);
        } else {
            lanes.updateFirst(used, meanTurn);
            for (int l = used; l < kShearLanes; ++l) {
                whole.nx[l] = whole.ny[l] = whole.nz[l] = 0.0;  // no direction: NaNs there
                whole.ux[l] = whole.uy[l] = whole.uz[l] = whole.sx[l] = whole.sy[l] = whole.sz[l] = 0.0;
                whole.stiffness[l] = whole.limit[l] = 0.0;
            }
            whole.update(meanTurn);
            for (int l = 0; l < used; ++l)
                ASSERT_TRUE(sameBits(whole.fx[l], lanes.fx[l]) && sameBits(whole.fy[l], lanes.fy[l]) &&
                            sameBits(whole.fz[l], lanes.fz[l]) && sameBits(whole.slid[l], lanes.slid[l]) &&
                            sameBits(whole.dissipated[l], lanes.dissipated[l]) &&
                            sameBits(whole.energy[l], lanes.energy[l]))
                    << "case " << first + static_cast<size_t>(l);
        }
        for (int l = 0; l < used; ++l) {
            const SpringCase& c = cases[first + static_cast<size_t>(l)];
            double dissipated = 0.0;
            const Vec3 expected = updateShearForce(c.stored, c.normal, c.slip, meanTurn.dot(c.normal),
                                                   c.stiffness, c.limit, &dissipated);
            ASSERT_TRUE(sameBits(lanes.fx[l], expected.x()) && sameBits(lanes.fy[l], expected.y()) &&
                        sameBits(lanes.fz[l], expected.z()))
                << "case " << first + static_cast<size_t>(l) << ": lane " << lanes.fx[l] << ", "
                << lanes.fy[l] << ", " << lanes.fz[l] << "; scalar " << expected.transpose();
            // What friction took: the scalar adds it only when the node slides.
            ASSERT_TRUE(sameBits(lanes.slid[l] != 0.0 ? 0.0 + lanes.dissipated[l] : 0.0, dissipated))
                << "case " << first + static_cast<size_t>(l);
            ASSERT_TRUE(sameBits(lanes.energy[l], 0.5 * expected.squaredNorm() / c.stiffness));
            (lanes.slid[l] != 0.0 ? sliding : sticking) += 1;
        }
    }
    // Both regimes were exercised in earnest.
    EXPECT_GT(sliding, 1000);
    EXPECT_GT(sticking, 1000);
}

TEST(ShearSpringLanes, SlipsAreThePointVelocitiesDifferenceTimesTheStep)
{
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto vec = [&] { return Vec3(unit(random), unit(random), unit(random)); };
    ContactGrain tester, other;
    tester.velocity = vec();
    tester.angularVelocity = 50.0 * vec();
    tester.pose.position = 3.0 * vec();
    other.velocity = vec();
    other.angularVelocity = 50.0 * vec();
    other.pose.position = 3.0 * vec();
    const double dt = 1.3e-6;
    const LaneBodyMotion a = LaneBodyMotion::of(tester.velocity, tester.angularVelocity,
                                                tester.pose.position);
    const LaneBodyMotion b = LaneBodyMotion::of(other.velocity, other.angularVelocity,
                                                other.pose.position);
    for (int batch = 0; batch < 100; ++batch) {
        ShearSpringLanes lanes;
        std::vector<Vec3> points;
        for (int l = 0; l < kShearLanes; ++l) {
            points.push_back(3.0 * vec());
            lanes.px[l] = points.back().x();
            lanes.py[l] = points.back().y();
            lanes.pz[l] = points.back().z();
        }
        // A part-filled batch below kShearLanesLeast (lane by lane) and above it (that many at
        // once, the rest lane by lane) gives the full batch's bits.
        ShearSpringLanes firstTwo = lanes, firstSix = lanes;
        lanes.slips(a, b, dt);
        firstTwo.slipsFirst(2, a, b, dt);
        firstSix.slipsFirst(6, a, b, dt);
        auto sameSlips = [&](const ShearSpringLanes& part, int l) {
            return sameBits(part.ux[l], lanes.ux[l]) && sameBits(part.uy[l], lanes.uy[l]) &&
                   sameBits(part.uz[l], lanes.uz[l]);
        };
        for (int l = 0; l < 6; ++l) {
            ASSERT_TRUE(sameSlips(firstSix, l)) << "lane " << l << " of six";
            if (l < 2) {
                ASSERT_TRUE(sameSlips(firstTwo, l)) << "lane " << l << " of two";
            }
        }
        for (int l = 0; l < kShearLanes; ++l) {
            const Vec3 expected = (tester.pointVelocity(points[static_cast<size_t>(l)]) -
                                   other.pointVelocity(points[static_cast<size_t>(l)])) *
                                  dt;
            ASSERT_TRUE(sameBits(lanes.ux[l], expected.x()) && sameBits(lanes.uy[l], expected.y()) &&
                        sameBits(lanes.uz[l], expected.z()));
        }
    }
}
