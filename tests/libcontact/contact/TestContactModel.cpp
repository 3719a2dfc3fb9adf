// The contact model and its small sub-models: node testing names, the accessors that hand out
// the normal, tangential and damping sub-models, the damping ratio from a restitution
// coefficient (against the damped oscillator for a linear spring, and against the energy a
// weak dashpot takes from an elastic impact for a stiffening one), and when shear springs act.
#include "lsdem/contact/ContactModel.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lsdem;

TEST(ContactModel, NodeTestingNamesRoundTripAndUnknownNamesAreRefused)
{
    EXPECT_EQ(nodeTestingName(NodeTesting::OneWay), "one-way");
    EXPECT_EQ(nodeTestingName(NodeTesting::Symmetric), "symmetric");
    for (NodeTesting t : {NodeTesting::OneWay, NodeTesting::Symmetric})
        EXPECT_EQ(parseNodeTesting(nodeTestingName(t)), t);
    try {
        parseNodeTesting("oneway");
        FAIL() << "no error for an unknown name";
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("'oneway'"), std::string::npos) << e.what();
        EXPECT_NE(e.fix().find("one-way"), std::string::npos);
        EXPECT_NE(e.fix().find("symmetric"), std::string::npos);
    }
}

TEST(ContactModel, HandsOutItsSubModels)
{
    const ContactModel defaults;
    EXPECT_EQ(defaults.formulation, Formulation::Adapted);      // docs/contact.md: the default
    EXPECT_EQ(defaults.testing, NodeTesting::Symmetric);        // likewise
    EXPECT_FALSE(defaults.damping.active());
    EXPECT_EQ(defaults.damping.restitution(), 1.0);
    EXPECT_FALSE(defaults.tangential().active(defaults.normal()));

    ContactModel m;
    m.normalStiffness = 2.0;
    m.shearStiffness = 3.0;
    m.friction = 0.4;
    m.damping = ViscousDamping(0.5);
    for (Formulation f : allFormulations()) {
        m.formulation = f;
        EXPECT_EQ(&m.normal(), &normalModel(f));  // the one shared instance
        EXPECT_EQ(stiffnessUnit(f), normalModel(f).stiffnessUnit());
    }
    const ShearSpringModel shear = m.tangential();
    EXPECT_EQ(shear.stiffness, 3.0);
    EXPECT_EQ(shear.friction, 0.4);
    EXPECT_EQ(m.damping.restitution(), 0.5);
    EXPECT_TRUE(m.damping.active());
}

// A linear spring-dashpot (p = 1) at ratio β < 1 of critical that may not pull: from x = 0,
// x' = 1 the body follows x = e^(−βt)·sin(ωt)/ω (ω = sqrt(1 − β²)) until the force
// x + 2βx' falls to zero, at ωt* = π − atan2(2βω, 1 − 2β²), where x' = −e^(−βt*) (worked out
// from the solution; Schwager & Pöschel's no-attraction linear dashpot): so
// e = exp(−β·t*) (below critical damping, which gives e = exp(−2) ≈ 0.135). The ratio for a restitution must
// invert that, to the quadrature's accuracy (2e-4: the force's kink at the release).
TEST(ContactModel, LinearSpringRatioInvertsTheNonPullingDampedOscillator)
{
    for (double e : {0.15, 0.3, 0.5, 0.8, 0.99}) {
        const double beta = dampingRatioFor(e, 1.0);
        EXPECT_GT(beta, 0.0);
        EXPECT_LT(beta, 1.0);
        const double omega = std::sqrt(1.0 - beta * beta);
        const double release = (kPi - std::atan2(2.0 * beta * omega, 1.0 - 2.0 * beta * beta)) / omega;
        EXPECT_NEAR(std::exp(-beta * release), e, 2e-4 * e) << e;
        EXPECT_EQ(ViscousDamping(e).ratio(1.0), beta);
    }
    // Heavier than critical still lets go, late and slowly.
    EXPECT_GT(dampingRatioFor(0.1, 1.0), 1.0);
    EXPECT_NEAR(restitutionOfImpact(dampingRatioFor(0.03, 1.0), 1.0), 0.03, 1e-6);
    EXPECT_EQ(dampingRatioFor(1.0, 1.0), 0.0);  // elastic: no dashpot
    EXPECT_EQ(ViscousDamping(1.0).ratio(2.0), 0.0);
    EXPECT_GT(dampingRatioFor(0.2, 1.0), dampingRatioFor(0.6, 1.0));  // less e, more damping
}

// A weak dashpot takes from an elastic impact x'' = -x^p (x' = 1 at x = 0) the energy
// ∫ 2β·sqrt(p·x^(p-1))·x'² dτ along the undamped path, which (x'² = 1 - 2x^(p+1)/(p+1), in and
// out) integrates by a Beta function to π·β·sqrt(2p/(p+1)); so e² = 1 - 2·that, and
// e ≈ 1 - π·β·sqrt(2p/(p+1)) to first order in β. At β = 1e-3 the second-order term is about
// πβ/2 ≈ 0.2 % of 1 - e, and the quadrature's own error about 0.3 %: 1 % tolerance.
TEST(ContactModel, StiffeningSpringRestitutionMatchesTheWeakDampingLimit)
{
    const double beta = 1e-3;
    for (double p : {1.0, 1.5, 2.0, 3.0, 4.0}) {
        const double loss = kPi * beta * std::sqrt(2.0 * p / (p + 1.0));
        EXPECT_NEAR(1.0 - restitutionOfImpact(beta, p), loss, 0.01 * loss) << "p = " << p;
    }
    EXPECT_EQ(restitutionOfImpact(0.0, 2.0), 1.0);
}

// For each exponent the ratio found for a restitution gives it back, a stiffening spring needs
// less damping than a linear one for the same loss (the weak-damping loss above grows with p),
// and the table interpolates between its exponents.
TEST(ContactModel, RatioForEachExponentGivesTheRestitutionBack)
{
    for (double e : {0.1, 0.5, 0.9}) {
        double previous = 0.0;
        for (double p : {1.0, 1.5, 2.0, 3.0, 4.0}) {
            const double beta = dampingRatioFor(e, p);
            EXPECT_NEAR(restitutionOfImpact(beta, p), e, 1e-10) << "e " << e << ", p " << p;
            if (p > 1.0) {
                EXPECT_LT(beta, previous) << "e " << e << ", p " << p;
            }
            previous = beta;
        }
        const ViscousDamping d(e);
        for (double p : {1.0, 2.0, 2.5, 4.0})  // table points: exact
            EXPECT_NEAR(d.ratio(p), dampingRatioFor(e, p), 1e-12);
        // Between points, within 0.3 % of the ratio (linear interpolation of a smooth curve
        // over steps of 1/8).
        EXPECT_NEAR(d.ratio(2.0625), dampingRatioFor(e, 2.0625), 3e-3 * d.ratio(2.0625));
        EXPECT_EQ(d.ratio(0.5), d.ratio(1.0));  // clamped to the table
        EXPECT_EQ(d.ratio(9.0), d.ratio(ViscousDamping::kLargestExponent));
        EXPECT_GE(d.largestRatio(), d.ratio(4.0));
    }
}

// A near-plastic restitution (found by fuzzing a scene: 5e-6 took a minute to calibrate, each
// heavily damped impact creeping out over the whole integration window): the body leaves by
// coasting once the force lets go, so it is calibrated as quickly as any other, and exactly.
TEST(ContactModel, ANearPlasticRestitutionIsCalibratedQuicklyAndExactly)
{
    for (double p : {1.0, 2.0, 4.0}) {
        const double beta = dampingRatioFor(5e-6, p);
        EXPECT_NEAR(restitutionOfImpact(beta, p), 5e-6, 1e-13) << "p " << p;
    }
    const ViscousDamping d(5e-6);  // the whole table, as a scene's contact builds it
    EXPECT_GT(d.ratio(2.0), d.ratio(4.0));
}

// The dashpot of a contact of stiffness K between effective mass m: c = 2β(p)·sqrt(m·K); none
// without damping, stiffness or a movable body. Restitution outside (0, 1] is refused.
TEST(ContactModel, DashpotIsTheCriticalFractionForTheExponent)
{
    const ViscousDamping d(0.4);
    EXPECT_NEAR(d.dashpot(2.5, 16.0, 2.0), 2 * d.ratio(2.0) * std::sqrt(2.5 * 16.0), 1e-14);
    EXPECT_EQ(ViscousDamping().dashpot(2.5, 16.0, 2.0), 0.0);
    EXPECT_EQ(d.dashpot(2.5, 0.0, 2.0), 0.0);
    EXPECT_EQ(d.dashpot(0.0, 16.0, 2.0), 0.0);
    EXPECT_THROW(ViscousDamping(0.0), std::invalid_argument);
    EXPECT_THROW(ViscousDamping(1.5), std::invalid_argument);
}

TEST(ContactModel, ShearSpringsActOnlyWithPerNodeForcesStiffnessAndFriction)
{
    for (Formulation f : allFormulations()) {
        const NormalModel& normal = normalModel(f);
        const bool perNode = f == Formulation::Original || f == Formulation::Adapted;
        EXPECT_EQ((ShearSpringModel{5.0, 0.3}.active(normal)), perNode) << formulationName(f);
        EXPECT_FALSE((ShearSpringModel{0.0, 0.3}.active(normal))) << formulationName(f);
        EXPECT_FALSE((ShearSpringModel{5.0, 0.0}.active(normal))) << formulationName(f);
    }
    // k_t of a node: ks per node (original), ks*·A per area (adapted), times the weight.
    const ShearSpringModel s{8.0, 0.3};
    EXPECT_EQ(s.nodeStiffness(normalModel(Formulation::Original), 0.25, 1.0), 8.0);
    EXPECT_EQ(s.nodeStiffness(normalModel(Formulation::Original), 0.25, 0.5), 4.0);
    EXPECT_EQ(s.nodeStiffness(normalModel(Formulation::Adapted), 0.25, 1.0), 2.0);
    EXPECT_EQ(s.nodeStiffness(normalModel(Formulation::Adapted), 0.25, 0.5), 1.0);
}
