// The contact model and its small sub-models: node testing names, the accessors that hand out
// the normal, tangential and damping sub-models, the damping ratio from a restitution
// coefficient against the damped oscillator, the dashpot share, and when shear springs act.
#include "lsdem/contact/ContactModel.h"
#include "lsdem/ls/Constants.h"
#include "lsdem/ls/Error.h"

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
    EXPECT_EQ(defaults.damping().ratio, 0.0);
    EXPECT_FALSE(defaults.tangential().active(defaults.normal()));

    ContactModel m;
    m.normalStiffness = 2.0;
    m.shearStiffness = 3.0;
    m.friction = 0.4;
    m.dampingRatio = 0.25;
    for (Formulation f : allFormulations()) {
        m.formulation = f;
        EXPECT_EQ(&m.normal(), &normalModel(f));  // the one shared instance
        EXPECT_EQ(stiffnessUnit(f), normalModel(f).stiffnessUnit());
    }
    const ShearSpringModel shear = m.tangential();
    EXPECT_EQ(shear.stiffness, 3.0);
    EXPECT_EQ(shear.friction, 0.4);
    EXPECT_EQ(m.damping().ratio, 0.25);
}

// A linear spring-dashpot at ratio β < 1 of critical rebounds after half a damped period with
// e = exp(-π·β/sqrt(1 - β²)) (the decay of the damped oscillator): fromRestitution must be its
// inverse, and it equals the closed form -ln e / sqrt(π² + ln² e).
TEST(ContactModel, DampingRatioFromRestitutionInvertsTheDampedOscillator)
{
    for (double e : {0.05, 0.3, 0.5, 0.8, 0.99}) {
        const double beta = ViscousDamping::fromRestitution(e).ratio;
        EXPECT_GT(beta, 0.0);
        EXPECT_LT(beta, 1.0);
        // The decay of a damped oscillator's half period, independent of how β is solved for.
        EXPECT_NEAR(std::exp(-kPi * beta / std::sqrt(1 - beta * beta)), e, 1e-14) << e;
        EXPECT_EQ(dampingRatioFromRestitution(e), beta);
    }
    EXPECT_EQ(ViscousDamping::fromRestitution(1.0).ratio, 0.0);  // elastic: no dashpot
    // Less restitution, more damping.
    EXPECT_GT(dampingRatioFromRestitution(0.2), dampingRatioFromRestitution(0.6));
}

// The dashpots of the point forces add up to the critical-damping fraction of the whole
// contact: Σ c_f = (c/k)·Σ k_f = 2β·sqrt(m/K)·K = 2β·sqrt(m·K).
TEST(ContactModel, DashpotPerStiffnessSharesTheContactDashpot)
{
    const ViscousDamping d{0.3};
    const double m = 2.5, stiffnesses[] = {1.0, 4.0, 0.5, 10.5};  // K = 16
    double total = 0.0;
    for (double k : stiffnesses) total += d.dashpotPerStiffness(m, 16.0) * k;
    EXPECT_NEAR(total, 2 * 0.3 * std::sqrt(2.5 * 16.0), 1e-14);
    EXPECT_NEAR(d.dashpotPerStiffness(m, 16.0), 2 * 0.3 * std::sqrt(2.5 / 16.0), 1e-15);
    // Nothing to damp without a ratio or without stiffness.
    EXPECT_EQ(ViscousDamping{0.0}.dashpotPerStiffness(m, 16.0), 0.0);
    EXPECT_EQ(d.dashpotPerStiffness(m, 0.0), 0.0);
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
