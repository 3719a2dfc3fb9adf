// Reference forces, in the manner of LAMMPS's force-style tests: for every formulation,
// tests/data/reference_forces/<formulation>.txt holds two bodies in six kinds of contact
// (grain–grain one-way and symmetric, grain–plane, grain–finite patch, grain–sphere indenter,
// grain–level-set obstacle) at two evaluations, with shear and damping on, and the forces,
// torques, node count and elastic energy the contact laws gave when the file was generated.
// This test recomputes them from the poses in the file and compares to 1e-12 of the force
// scale: the computation is deterministic (fixed assets, fixed order of sums), so the tolerance
// only absorbs rounding differences between compilers (FMA contraction, vectorisation).
//
// Every run also checks the file's numbers against closed forms and conservation laws
// (plausibilityChecks: Newton's third law, moment balance, k·π·R·δ² and the like, the shear
// history's effect). To regenerate after an intended change of a law, from a clean commit (it
// refuses otherwise; review the diff and the checks in the header):
//   LSDEM_REGENERATE_REFERENCE=1 build/tests/test_contact --gtest_filter='*ReferenceForces*'
#include "libcontact/contact/ReferenceForces.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>

using namespace lsdem;
using namespace lsdem::test::reference;

namespace {

constexpr double kTolerance = 1e-12;

bool regenerating()
{
    const char* value = std::getenv("LSDEM_REGENERATE_REFERENCE");
    return value && std::string(value) == "1";
}

void expectClose(const Vec3& actual, const Vec3& expected, double tolerance, const char* what)
{
    for (int k = 0; k < 3; ++k)
        EXPECT_LE(std::abs(actual[k] - expected[k]), tolerance)
            << what << "[" << k << "]: " << actual[k] << " computed, " << expected[k]
            << " in the file";
}

class ReferenceForces : public ::testing::TestWithParam<Formulation>
{
};

} // namespace

TEST_P(ReferenceForces, RecomputedForcesMatchTheFile)
{
    const Formulation f = GetParam();
    const std::string path = referenceFilePath(f);
    if (regenerating()) {
        // From a clean commit only: the header names the commit that reproduces the file.
        const std::string changes = uncommittedChanges();
        ASSERT_TRUE(changes.empty()) << "commit (or stash) these changes before regenerating "
                                     << path << ":\n"
                                     << changes;
        const std::vector<Case> generated = generateCases(f);
        writeReferenceFile(path, f, generated, plausibilityChecks(f, generated));
        std::cout << "regenerated " << path << "\n";
    }
    std::vector<Case> cases;
    Formulation inFile = f;
    try {
        cases = readReferenceFile(path, inFile);
    } catch (const std::exception& e) {
        FAIL() << e.what();
    }
    EXPECT_EQ(inFile, f);
    ASSERT_EQ(cases.size(), kindNames().size());
    for (size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        EXPECT_EQ(c.kind, kindNames()[k]);
        ASSERT_EQ(c.evaluations.size(), 2u) << c.kind;
        const std::vector<Outcome> computed = evaluate(c);
        for (size_t e = 0; e < computed.size(); ++e) {
            SCOPED_TRACE(c.kind + ", evaluation " + std::to_string(e + 1));
            const Outcome& want = c.expected[e];
            const Outcome& got = computed[e];
            const double forceScale = std::max(want.forceFirst.norm(), want.forceSecond.norm());
            ASSERT_GT(forceScale, 0.0);
            // Torques are sums of lever × force with levers up to the distance between the
            // bodies' reference points plus the grain's size.
            const Vec3 second = isGrainPair(c)
                                    ? c.evaluations[e].second.pose.position
                                    : (c.boundary.shape == BoundaryShape::Plane
                                           ? c.boundary.plane.point
                                           : c.boundary.shape == BoundaryShape::Sphere
                                                 ? c.boundary.center
                                                 : c.boundary.pose.position) +
                                          c.evaluations[e].boundaryDisplacement;
            const double lever = (c.evaluations[e].first.pose.position - second).norm() +
                                 referenceAsset(c.firstAsset).boundingRadius;
            EXPECT_EQ(got.nodes, want.nodes);
            expectClose(got.forceFirst, want.forceFirst, kTolerance * forceScale, "force_first");
            expectClose(got.forceSecond, want.forceSecond, kTolerance * forceScale,
                        "force_second");
            expectClose(got.torqueFirst, want.torqueFirst, kTolerance * forceScale * lever,
                        "torque_first");
            expectClose(got.torqueSecond, want.torqueSecond, kTolerance * forceScale * lever,
                        "torque_second");
            EXPECT_NEAR(got.elasticEnergy, want.elasticEnergy, kTolerance * want.elasticEnergy);
            // The stored numbers themselves obey action and reaction.
            EXPECT_LE((want.forceFirst + want.forceSecond).norm(), kTolerance * forceScale);
        }
    }
    // The file's numbers against closed forms and conservation laws, on every run (not only
    // when it was generated): the fixture cannot drift into confirming a wrong law.
    plausibilityChecks(f, cases);
}

INSTANTIATE_TEST_SUITE_P(Formulation, ReferenceForces, ::testing::ValuesIn(allFormulations()),
                         [](const ::testing::TestParamInfo<Formulation>& param) {
                             std::string name = formulationName(param.param);
                             for (char& ch : name)
                                 if (ch == '-') ch = '_';
                             return name;
                         });

// A hand-edited file that is wrong says where: the file, the line and the key.
TEST(ReferenceForceFile, MalformedValuesAreReportedWithTheirLine)
{
    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("bad.txt");
    std::ofstream(path) << "# comment\nformulation adapted\n\ncase grain-plane\ntesting one-way\n"
                           "model 1000 800 0.4 x\n";
    Formulation f = Formulation::Original;
    try {
        readReferenceFile(path, f);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:6: model"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readReferenceFile(dir.file("missing.txt"), f), std::runtime_error);
}
