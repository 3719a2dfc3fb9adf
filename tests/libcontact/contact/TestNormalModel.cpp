// The four normal sub-models (original, adapted, single-node, volume): what each says about
// itself, and the point forces it makes from a hand-made list of penetrating nodes, against
// sums worked out here; weight scaling; and formulation names.
#include "lsdem/contact/NormalModel.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

using namespace lsdem;

namespace {

NodeContact node(int index, double depth, const Vec3& normal, const Vec3& point, double area)
{
    NodeContact c;
    c.node = index;
    c.depth = depth;
    c.normal = normal.normalized();
    c.point = point;
    c.area = area;
    return c;
}

/// Four nodes with different depths, normals, points and areas; nodes 3 and 8 tie as deepest.
std::vector<NodeContact> handMadeContacts()
{
    return {node(3, 0.25, Vec3(0, 0, 1), Vec3(0.5, 0, 0), 0.5),
            node(5, 0.125, Vec3(0, 3, 4), Vec3(0, 1, 0), 2.0),
            node(8, 0.25, Vec3(1, 0, 0), Vec3(0, 0, 2), 0.25),
            node(9, 0.0625, Vec3(0, 0, 1), Vec3(-1, -1, 0), 1.0)};
}

// Vectors built from binary fractions: the products below are exact, so compare with a
// relative 1e-15 only for the normalised (0, 0.6, 0.8).
void expectVecNear(const Vec3& a, const Vec3& b, double scale)
{
    EXPECT_LT((a - b).norm(), 1e-15 * scale) << a.transpose() << " vs " << b.transpose();
}

} // namespace

TEST(NormalModel, EachSubModelDescribesItselfAsDocumented)
{
    const NormalModel& original = normalModel(Formulation::Original);
    const NormalModel& adapted = normalModel(Formulation::Adapted);
    const NormalModel& single = normalModel(Formulation::SingleNode);
    const NormalModel& volume = normalModel(Formulation::Volume);
    EXPECT_EQ(original.name(), "original");
    EXPECT_EQ(adapted.name(), "adapted");
    EXPECT_EQ(single.name(), "single-node");
    EXPECT_EQ(volume.name(), "volume");
    for (Formulation f : allFormulations()) EXPECT_EQ(normalModel(f).formulation(), f);

    // Units: per-node springs are force/length; per-area ones force/length³.
    EXPECT_EQ(original.stiffnessUnit(), "force/length");
    EXPECT_EQ(single.stiffnessUnit(), "force/length");
    EXPECT_EQ(adapted.stiffnessUnit().rfind("force/length^3", 0), 0u);
    EXPECT_EQ(volume.stiffnessUnit().rfind("force/length^3", 0), 0u);

    EXPECT_FALSE(original.stiffnessPerArea());
    EXPECT_TRUE(adapted.stiffnessPerArea());
    EXPECT_FALSE(single.stiffnessPerArea());
    EXPECT_TRUE(volume.stiffnessPerArea());
    // Only the laws with a force per node can carry per-node shear springs.
    EXPECT_TRUE(original.perNodeForces());
    EXPECT_TRUE(adapted.perNodeForces());
    EXPECT_FALSE(single.perNodeForces());
    EXPECT_FALSE(volume.perNodeForces());
    // The paper's values in mm and N: kn = 1 GN/mm, kn* = 1 GPa/mm = 1e3 N/mm³.
    EXPECT_EQ(original.paperStiffness(), 1e9);
    EXPECT_EQ(adapted.paperStiffness(), 1e3);
    EXPECT_EQ(single.paperStiffness(), 1e9);
    EXPECT_EQ(volume.paperStiffness(), 1e3);

    // One node of area 0.5 with k = 8: k·A per area, k per node.
    EXPECT_EQ(original.nodeStiffness(8.0, 0.5), 8.0);
    EXPECT_EQ(adapted.nodeStiffness(8.0, 0.5), 4.0);
    EXPECT_EQ(single.nodeStiffness(8.0, 0.5), 8.0);
    EXPECT_EQ(volume.nodeStiffness(8.0, 0.5), 4.0);
    // A flat patch of area 6 covered by nodes of area 0.5 (12 nodes), k = 8: 12 springs for the
    // original law, the traction integral k·6 for the per-area laws, one spring for single-node.
    EXPECT_EQ(original.patchStiffness(8.0, 6.0, 0.5), 96.0);
    EXPECT_EQ(adapted.patchStiffness(8.0, 6.0, 0.5), 48.0);
    EXPECT_EQ(single.patchStiffness(8.0, 6.0, 0.5), 8.0);
    EXPECT_EQ(volume.patchStiffness(8.0, 6.0, 0.5), 48.0);
}

TEST(NormalModel, OriginalIsKnTimesDepthAlongTheNormalAtEveryNode)
{
    const auto contacts = handMadeContacts();
    std::vector<PointForce> out(1);  // appends
    normalModel(Formulation::Original).forces(contacts, 8.0, 1.0, out);
    ASSERT_EQ(out.size(), 5u);
    expectVecNear(out[1].force, Vec3(0, 0, 2), 2);         // 8·0.25
    expectVecNear(out[2].force, Vec3(0, 0.6, 0.8), 1);     // 8·0.125 along (0, .6, .8)
    expectVecNear(out[3].force, Vec3(2, 0, 0), 2);
    expectVecNear(out[4].force, Vec3(0, 0, 0.5), 1);
    for (size_t k = 0; k < contacts.size(); ++k) {
        EXPECT_EQ(out[k + 1].node, contacts[k].node);
        EXPECT_EQ(out[k + 1].point, contacts[k].point);
        EXPECT_EQ(out[k + 1].stiffness, 8.0);
    }
}

TEST(NormalModel, AdaptedIsTractionTimesAreaAtEveryNode)
{
    const auto contacts = handMadeContacts();
    std::vector<PointForce> out;
    normalModel(Formulation::Adapted).forces(contacts, 8.0, 1.0, out);
    ASSERT_EQ(out.size(), 4u);
    expectVecNear(out[0].force, Vec3(0, 0, 1), 1);         // 8·0.25·0.5
    expectVecNear(out[1].force, Vec3(0, 1.2, 1.6), 2);     // 8·0.125·2
    expectVecNear(out[2].force, Vec3(0.5, 0, 0), 1);       // 8·0.25·0.25
    expectVecNear(out[3].force, Vec3(0, 0, 0.5), 1);       // 8·0.0625·1
    const double areas[] = {0.5, 2.0, 0.25, 1.0};
    for (size_t k = 0; k < contacts.size(); ++k) {
        EXPECT_EQ(out[k].node, contacts[k].node);
        EXPECT_EQ(out[k].point, contacts[k].point);
        EXPECT_EQ(out[k].stiffness, 8.0 * areas[k]);
    }
}

TEST(NormalModel, SingleNodeTakesTheFirstOfTheDeepestNodes)
{
    auto contacts = handMadeContacts();
    std::vector<PointForce> out;
    normalModel(Formulation::SingleNode).forces(contacts, 8.0, 1.0, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].node, 3);  // nodes 3 and 8 are both 0.25 deep: the first wins
    expectVecNear(out[0].force, Vec3(0, 0, 2), 2);
    EXPECT_EQ(out[0].point, contacts[0].point);
    EXPECT_EQ(out[0].stiffness, 8.0);
    // Make node 8 strictly deeper: it wins.
    contacts[2].depth = 0.5;
    out.clear();
    normalModel(Formulation::SingleNode).forces(contacts, 8.0, 1.0, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].node, 8);
    expectVecNear(out[0].force, Vec3(4, 0, 0), 4);
    // No penetrating node, no force.
    out.clear();
    normalModel(Formulation::SingleNode).forces({}, 8.0, 1.0, out);
    EXPECT_TRUE(out.empty());
}

// V = Σ d·A = 0.125 + 0.25 + 0.0625 + 0.0625 = 0.5; Σ d·A·n = (0.0625, 0.15, 0.125 + 0.2 +
// 0.0625) = (0.0625, 0.15, 0.3875); the centroid Σ d·A·p / V; stiffness kv·Σ A = 8·3.75.
TEST(NormalModel, VolumeIsKvTimesTheOverlapAlongTheMeanNormalAtTheWeightedCentroid)
{
    const auto contacts = handMadeContacts();
    std::vector<PointForce> out;
    normalModel(Formulation::Volume).forces(contacts, 8.0, 1.0, out);
    ASSERT_EQ(out.size(), 1u);
    const Vec3 direction = Vec3(0.0625, 0.15, 0.3875).normalized();
    expectVecNear(out[0].force, 8.0 * 0.5 * direction, 4);
    const Vec3 centroid =
        (0.125 * Vec3(0.5, 0, 0) + 0.25 * Vec3(0, 1, 0) + 0.0625 * Vec3(0, 0, 2) +
         0.0625 * Vec3(-1, -1, 0)) / 0.5;
    expectVecNear(out[0].point, centroid, 1);
    EXPECT_EQ(out[0].node, -1);  // pooled: no node of its own
    EXPECT_EQ(out[0].stiffness, 8.0 * 3.75);
    // Nothing penetrating, or normals that cancel: no force (no direction to push).
    out.clear();
    normalModel(Formulation::Volume).forces({}, 8.0, 1.0, out);
    EXPECT_TRUE(out.empty());
    const std::vector<NodeContact> opposed = {node(0, 0.5, Vec3(1, 0, 0), Vec3::Zero(), 1.0),
                                              node(1, 0.5, Vec3(-1, 0, 0), Vec3::Zero(), 1.0)};
    normalModel(Formulation::Volume).forces(opposed, 8.0, 1.0, out);
    EXPECT_TRUE(out.empty());
}

// Symmetric testing runs each direction at half weight: forces and stiffnesses halve exactly,
// points and nodes do not change.
TEST(NormalModel, WeightScalesForcesAndStiffnesses)
{
    const auto contacts = handMadeContacts();
    for (Formulation f : allFormulations()) {
        std::vector<PointForce> full, half;
        normalModel(f).forces(contacts, 8.0, 1.0, full);
        normalModel(f).forces(contacts, 8.0, 0.5, half);
        ASSERT_EQ(full.size(), half.size()) << formulationName(f);
        for (size_t k = 0; k < full.size(); ++k) {
            EXPECT_EQ(half[k].force, 0.5 * full[k].force) << formulationName(f);
            EXPECT_EQ(half[k].stiffness, 0.5 * full[k].stiffness) << formulationName(f);
            EXPECT_EQ(half[k].point, full[k].point) << formulationName(f);
            EXPECT_EQ(half[k].node, full[k].node) << formulationName(f);
        }
    }
}

// The contact law reads a per-node force's size and direction from its contact (k·d along
// the unit normal) instead of recovering them from the force: every per-node law must give
// each contact exactly one force k·d·n with stiffness k, in the contacts' order, whatever that
// order is (here also reversed, not sorted by node).
TEST(NormalModel, PerNodeForcesAreStiffnessTimesDepthAlongEachContactsNormal)
{
    const std::vector<NodeContact> ascending = handMadeContacts();
    const std::vector<NodeContact> reversed(ascending.rbegin(), ascending.rend());
    int perNodeLaws = 0;
    for (Formulation f : allFormulations()) {
        if (!normalModel(f).perNodeForces()) continue;
        ++perNodeLaws;
        for (const std::vector<NodeContact>* contacts : {&ascending, &reversed}) {
            SCOPED_TRACE(formulationName(f) + (contacts == &reversed ? ", reversed" : ""));
            std::vector<PointForce> out;
            normalModel(f).forces(*contacts, 8.0, 0.5, out);
            ASSERT_EQ(out.size(), contacts->size());
            for (size_t k = 0; k < contacts->size(); ++k) {
                const NodeContact& c = (*contacts)[k];
                EXPECT_EQ(out[k].node, c.node);
                EXPECT_GT(out[k].stiffness, 0.0);
                const Vec3 expected = out[k].stiffness * c.depth * c.normal;
                expectVecNear(out[k].force, expected, expected.norm());
            }
        }
    }
    EXPECT_EQ(perNodeLaws, 2);  // original and adapted
}

TEST(NormalModel, FormulationNamesRoundTripAndUnknownNamesAreRefused)
{
    const std::vector<Formulation> expected = {Formulation::Original, Formulation::Adapted,
                                               Formulation::SingleNode, Formulation::Volume};
    EXPECT_EQ(allFormulations(), expected);
    for (Formulation f : allFormulations()) {
        EXPECT_EQ(parseFormulation(formulationName(f)), f);
        EXPECT_EQ(formulationName(f), normalModel(f).name());
    }
    try {
        parseFormulation("Adapted");  // names are case-sensitive
        FAIL() << "no error for an unknown name";
    } catch (const Error& e) {
        EXPECT_NE(e.problem().find("'Adapted'"), std::string::npos) << e.what();
        EXPECT_EQ(e.fix(), "use one of: original, adapted, single-node, volume");
    }
    EXPECT_THROW(parseFormulation(""), Error);
}

// The traction a law acts like: a flat patch of n nodes of area A each, all pressed to depth d
// along one normal, is pushed by traction·(n·A)·d — the law's own forces() summed. A law
// without a traction (single-node) pushes the same however many nodes touch.
TEST(NormalModel, TractionStiffnessIsWhatAFlatPatchOfNodesPressesWith)
{
    const double k = 7.0, area = 0.3, depth = 0.02;
    auto patchForce = [&](const NormalModel& law, int n) {
        std::vector<NodeContact> patch;
        for (int i = 0; i < n; ++i)
            patch.push_back(node(i, depth, Vec3(0, 0, 1), Vec3(0.1 * i, 0, 0), area));
        std::vector<PointForce> forces;
        law.forces(patch, k, 1.0, forces);
        Vec3 sum = Vec3::Zero();
        for (const PointForce& f : forces) sum += f.force;
        return sum.z();
    };
    for (Formulation f : allFormulations()) {
        const NormalModel& law = normalModel(f);
        const std::optional<double> traction = law.tractionStiffness(k, area);
        if (!traction) {
            EXPECT_FALSE(law.stiffnessPerArea()) << law.name();
            EXPECT_DOUBLE_EQ(patchForce(law, 12), patchForce(law, 1)) << law.name();
            EXPECT_FALSE(law.stiffnessForTraction(1.0, area)) << law.name();
            continue;
        }
        for (int n : {1, 12})
            EXPECT_NEAR(patchForce(law, n), *traction * n * area * depth, 1e-12) << law.name();
        // The inverse, and a law per area's traction is its stiffness whatever the nodes.
        EXPECT_NEAR(*law.stiffnessForTraction(*traction, area), k, 1e-12 * k) << law.name();
        if (law.stiffnessPerArea()) {
            EXPECT_EQ(*law.tractionStiffness(k, 5.0 * area), k);
        }
        EXPECT_EQ(law.convergesWithNodes(), law.stiffnessPerArea()) << law.name();
    }
}

// Each law's continuum limit for two spheres tends to the leading order (π/2)·k·R·δ² as
// δ/R → 0; the volume law's own integral (no projection on the centre line) exceeds the
// traction integral by about δ/(6R) (SphereContactReference.h).
TEST(NormalModel, ContinuumSphereForceIsEachLawsOwnLimit)
{
    const double radius = 5.0, k = 1e3;
    for (Formulation f : allFormulations()) {
        const NormalModel& law = normalModel(f);
        if (!law.tractionStiffness(k, 1.0)) continue;
        const double small = 1e-3;
        EXPECT_NEAR(law.continuumSphereForce(radius, small, k) /
                        (0.5 * 3.141592653589793 * k * radius * small * small),
                    1.0, 1e-3)
            << law.name();
    }
    const double delta = 0.1;  // δ/R = 0.02: the volume law 0.33 % above
    const double ratio = normalModel(Formulation::Volume).continuumSphereForce(radius, delta, k) /
                         normalModel(Formulation::Adapted).continuumSphereForce(radius, delta, k);
    EXPECT_NEAR(ratio - 1.0, delta / (6.0 * radius), 0.1 * delta / (6.0 * radius));
    EXPECT_EQ(normalModel(Formulation::Original).continuumSphereForce(radius, delta, k),
              normalModel(Formulation::Adapted).continuumSphereForce(radius, delta, k));
}

// Messages name the formulations that have a property from the registry, not from a list
// written beside them.
TEST(NormalModel, FormulationNamesWhereListsThoseWithTheProperty)
{
    EXPECT_EQ(formulationNamesWhere(&NormalModel::perNodeForces), "original or adapted");
    EXPECT_EQ(formulationNamesWhere(&NormalModel::stiffnessPerArea, "'"), "'adapted' or 'volume'");
    EXPECT_EQ(formulationNamesWhere(&NormalModel::convergesWithNodes), "adapted or volume");
}
