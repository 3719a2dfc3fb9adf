// The [[contacts]] schema (ContactCoefficients.h): each coefficient's range refuses what it
// should and nothing else, the rules between sub-models name the key at fault, a written scene
// carries what is not at its default, and docs/scenes.md's table says what the schema says.
#include "lsdem/contact/ContactCoefficients.h"
#include "lsdem/core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

using namespace lsdem;

namespace {

ContactModel adaptedWith(double ks, double mu)
{
    ContactModel m;
    m.formulation = Formulation::Adapted;
    m.normalStiffness = 1e3;
    m.shearStiffness = ks;
    m.friction = mu;
    return m;
}

} // namespace

TEST(ContactCoefficients, EachSubModelBringsItsOwnInTheWrittenOrder)
{
    std::vector<std::string> keys, subModels;
    for (const ContactCoefficient& k : contactCoefficients()) {
        keys.push_back(k.key);
        subModels.push_back(k.subModel);
    }
    EXPECT_EQ(keys, (std::vector<std::string>{"normal_stiffness", "shear_stiffness", "friction",
                                              "restitution"}));
    EXPECT_EQ(subModels, (std::vector<std::string>{"normal", "tangential", "tangential", "damping"}));
    EXPECT_FALSE(contactCoefficient("normal_stiffness").defaultValue);  // required
    EXPECT_EQ(contactCoefficientDefault("restitution"), 1.0);
    EXPECT_THROW(contactCoefficient("stiffness"), std::out_of_range);
    EXPECT_THROW(contactCoefficientDefault("normal_stiffness"), std::out_of_range);
}

TEST(ContactCoefficients, RangesRefuseWhatTheySayAndNothingElse)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (const ContactCoefficient& k : contactCoefficients()) {
        for (double bad : {nan, inf, -inf, -1.0}) {
            const auto p = k.rangeProblem(bad);
            ASSERT_TRUE(p) << k.key << " accepted " << bad;
            EXPECT_EQ(p->key, k.key);
            EXPECT_NE(p->problem.find("must be " + k.rangeText()), std::string::npos) << p->problem;
            EXPECT_FALSE(p->fix.empty());
        }
        EXPECT_FALSE(k.rangeProblem(0.5)) << k.key;
        EXPECT_FALSE(k.rangeProblem(1.0)) << k.key;
        // Zero: allowed only where the range includes it.
        EXPECT_EQ(k.rangeProblem(0.0).has_value(), k.range != NumberRange::NonNegative) << k.key;
        // Above one: refused only for the restitution.
        EXPECT_EQ(k.rangeProblem(1.5).has_value(), k.range == NumberRange::PositiveFraction) << k.key;
    }
}

TEST(ContactCoefficients, TheRulesBetweenSubModelsNameTheKeyAtFault)
{
    EXPECT_FALSE(checkContactModel(adaptedWith(500.0, 0.3)));
    EXPECT_FALSE(checkContactModel(adaptedWith(500.0, 0.0)));  // springs without a cap: elastic
    EXPECT_FALSE(checkContactModel(adaptedWith(0.0, 0.0)));

    const auto noSprings = checkContactModel(adaptedWith(0.0, 0.3));
    ASSERT_TRUE(noSprings);
    EXPECT_EQ(noSprings->key, "friction");

    ContactModel single = adaptedWith(500.0, 0.0);
    single.formulation = Formulation::SingleNode;
    const auto shear = checkContactModel(single, "'");
    ASSERT_TRUE(shear);
    EXPECT_EQ(shear->key, "shear_stiffness");
    EXPECT_NE(shear->problem.find("'single-node'"), std::string::npos) << shear->problem;
    // The fix names the laws that can carry shear springs, from the registry.
    EXPECT_NE(shear->fix.find(formulationNamesWhere(&NormalModel::perNodeForces, "'")),
              std::string::npos) << shear->fix;

    ContactModel volume = adaptedWith(0.0, 0.3);
    volume.formulation = Formulation::Volume;
    const auto friction = checkContactModel(volume);
    ASSERT_TRUE(friction);
    EXPECT_EQ(friction->key, "friction");

    ContactModel soft = adaptedWith(0.0, 0.0);
    soft.normalStiffness = 0.0;
    const auto stiffness = checkContactModel(soft);
    ASSERT_TRUE(stiffness);
    EXPECT_EQ(stiffness->key, "normal_stiffness");  // ranges come before the rules
}

TEST(ContactCoefficients, OnlyWhatIsRequiredOrNotAtItsDefaultIsWritten)
{
    ContactModel m = adaptedWith(0.0, 0.0);
    std::set<std::string> written;
    for (const ContactCoefficient& k : contactCoefficients())
        if (k.written(m)) written.insert(k.key);
    EXPECT_EQ(written, (std::set<std::string>{"normal_stiffness"}));

    m = adaptedWith(500.0, 0.3);
    m.damping = ViscousDamping(0.5);
    written.clear();
    for (const ContactCoefficient& k : contactCoefficients()) {
        if (k.written(m)) written.insert(k.key);
        // What is set is what is read back.
        ContactModel copy;
        k.set(copy, k.get(m));
        EXPECT_EQ(k.get(copy), k.get(m)) << k.key;
    }
    EXPECT_EQ(written.size(), contactCoefficients().size());
    // The stiffness's unit follows the formulation: per area for adapted, per node for original.
    EXPECT_EQ(contactCoefficient("normal_stiffness").unit(m).rfind("force/length^3", 0), 0u);
    m.formulation = Formulation::Original;
    const std::string perNode = contactCoefficient("normal_stiffness").unit(m);
    EXPECT_EQ(perNode.rfind("force/length", 0), 0u);
    EXPECT_EQ(perNode.find("^3"), std::string::npos) << perNode;
    EXPECT_FALSE(contactCoefficient("friction").unit);  // a pure number
}

// docs/scenes.md's [[contacts]] table has a row for every coefficient, whose last column gives
// its default ("required, > 0" for one without), and no row for a number the schema lacks.
TEST(ContactCoefficients, ScenesMdTableAgreesWithTheSchema)
{
    std::ifstream in(LSDEM_SOURCE_DIR "/docs/scenes.md");
    ASSERT_TRUE(in) << "docs/scenes.md not found";
    std::string line;
    bool inSection = false;
    std::map<std::string, std::string> defaults;  // key → last column
    while (std::getline(in, line)) {
        if (line.rfind("## ", 0) == 0) inSection = line.find("[[contacts]]") != std::string::npos;
        if (!inSection || line.rfind("| `", 0) != 0) continue;
        const size_t keyEnd = line.find('`', 3);
        const std::string key = line.substr(3, keyEnd - 3);
        const size_t last = line.rfind(" | ");
        defaults[key] = line.substr(last + 3, line.size() - last - 5);
    }
    ASSERT_FALSE(defaults.empty()) << "no [[contacts]] table in docs/scenes.md";
    std::set<std::string> schemaKeys;
    for (const ContactCoefficient& k : contactCoefficients()) {
        schemaKeys.insert(k.key);
        ASSERT_TRUE(defaults.count(k.key)) << k.key << " is not in docs/scenes.md";
        std::ostringstream expected;
        if (k.defaultValue)
            expected << *k.defaultValue;
        else
            expected << "required, " << k.rangeText();
        EXPECT_EQ(defaults[k.key], expected.str()) << k.key;
    }
    // The words: each choice's row gives its default as a name in backticks.
    for (const ContactChoice& k : contactChoices()) {
        schemaKeys.insert(k.key);
        ASSERT_TRUE(defaults.count(k.key)) << k.key << " is not in docs/scenes.md";
        EXPECT_EQ(defaults[k.key], "`" + k.defaultValue() + "`") << k.key;
    }
    // The other row is the pair of materials.
    for (const auto& [key, value] : defaults) {
        if (schemaKeys.count(key)) continue;
        EXPECT_EQ(key, "materials = [\"a\", \"b\"]")
            << "docs/scenes.md lists '" << key << "', which the schema does not know";
    }
}

// Each choice takes each of its names and gives it back, refuses any other naming the ones it
// takes, and its default is what a ContactModel{} holds; only the quadrature is left out of a
// written scene at its default.
TEST(ContactCoefficients, ChoicesTakeTheirNamesAndRefuseOthers)
{
    std::vector<std::string> keys;
    for (const ContactChoice& k : contactChoices()) {
        keys.push_back(k.key);
        for (const std::string& value : k.values) {
            ContactModel m;
            k.set(m, value);
            EXPECT_EQ(k.get(m), value) << k.key;
        }
        ContactModel m;
        try {
            k.set(m, "magic");
            ADD_FAILURE() << k.key << " took 'magic'";
        } catch (const Error& e) {
            const std::string what = e.what();
            for (const std::string& value : k.values)
                EXPECT_NE(what.find(value), std::string::npos) << k.key << ": " << what;
        }
        EXPECT_TRUE(k.written(ContactModel{}) == (k.key != "quadrature")) << k.key;
    }
    EXPECT_EQ(keys, (std::vector<std::string>{"formulation", "testing", "quadrature"}));
    EXPECT_EQ(contactChoice("formulation").defaultValue(), formulationName(ContactModel{}.formulation));
    EXPECT_EQ(contactChoice("testing").defaultValue(), "symmetric");
    EXPECT_EQ(contactChoice("quadrature").defaultValue(), "node");
    ContactModel patch;
    contactChoice("quadrature").set(patch, "patch");
    EXPECT_TRUE(contactChoice("quadrature").written(patch));
    EXPECT_THROW(contactChoice("colour"), std::out_of_range);
}
