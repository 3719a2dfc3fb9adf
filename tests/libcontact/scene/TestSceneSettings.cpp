// The settings schema (SceneSettings.h): each setting's range refuses what it should, in a file
// and in validateScene with the same words; every setting written reads back as it was; and
// docs/scenes.md's [simulation] and [output] tables list exactly the schema's keys, with its
// defaults. (Python's properties, made from the same schema: python/tests/test_scenes.py.)
#include "lsdem/scene/SceneSettings.h"

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/SceneFile.h"
#include "lsdem/scene/SceneValidation.h"
#include "lsdem/scene/SceneWriter.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

using namespace lsdem;

namespace {

const std::string kScene = R"(
[assets.ball]
shape = "sphere"
radius = 1.0
voxel = 0.1
nodes = 200

[materials.steel]
density = 7.85e-9

[[contacts]]
materials = ["steel", "steel"]
normal_stiffness = 1e3

[[grains]]
asset = "ball"
material = "steel"
position = [0, 0, 0]

[simulation]
end_steps = 10

[output]
)";

/// kScene with `line` at the start of @a section (in place of the line of the same key).
std::string withLine(const std::string& section, const std::string& line)
{
    std::string text = kScene;
    const std::string key = line.substr(0, line.find(' '));
    if (const size_t old = text.find("\n" + key + " = "); old != std::string::npos)
        text.erase(old + 1, text.find('\n', old + 1) - old);
    const std::string header = "[" + section + "]\n";
    const size_t at = text.find(header) + header.size();
    return text.insert(at, line + "\n");
}

/// A value of @a s's type outside its range, as a Scene holds it, and as a file writes it.
SettingValue outOfRange(const SceneSetting& s)
{
    const SettingValue kind = s.defaultValue();
    if (std::holds_alternative<Vec3>(kind))  // a component below a vector's range, or NaN
        return s.range == NumberRange::NonNegative ? Vec3(0.0, -1.0, 0.0) : Vec3(0.0, 0.0, std::nan(""));
    if (std::holds_alternative<long long>(kind)) return -1LL;
    switch (s.range) {
    case NumberRange::Fraction: return 1.0;
    case NumberRange::PositiveFraction: return 2.0;
    default: return -1.0;
    }
}

/// A value in range and not the default (so a scene must write it).
SettingValue inRangeNotDefault(const SceneSetting& s)
{
    const SettingValue kind = s.defaultValue();
    if (std::holds_alternative<Vec3>(kind))
        return s.range == NumberRange::NonNegative ? Vec3(0.5, 1.0, 9810.0) : Vec3(0.5, -1.0, -9810.0);
    if (std::holds_alternative<long long>(kind)) return 7LL;
    if (const bool* b = std::get_if<bool>(&kind)) return !*b;
    return s.range == NumberRange::Fraction ? 0.25 : 0.3;
}

} // namespace

TEST(SceneSettings, RangesRefuseWhatTheySayAndNothingElse)
{
    for (const SceneSetting& s : sceneSettings()) {
        if (std::holds_alternative<bool>(s.defaultValue())) {
            EXPECT_FALSE(s.problem(true)) << s.key;
            EXPECT_FALSE(s.problem(false)) << s.key;
            continue;
        }
        EXPECT_FALSE(s.problem(s.defaultValue())) << s.key << ": its default is in range";
        EXPECT_FALSE(s.problem(inRangeNotDefault(s))) << s.key;
        const std::optional<std::string> p = s.problem(outOfRange(s));
        ASSERT_TRUE(p) << s.key;
        EXPECT_EQ(p->rfind("must be ", 0), 0u) << *p;
        if (std::holds_alternative<double>(s.defaultValue())) {
            EXPECT_TRUE(s.problem(std::nan(""))) << s.key << ": NaN is in no range";
        }
        EXPECT_TRUE(s.problem(SettingValue(true))) << s.key << ": a value of another type";
    }
}

// The same value out of range is refused by the reader (at the key's line) and by
// validateScene (which buildWorld, the writer and Python's setters call) in the same words.
TEST(SceneSettings, FileAndValidationRefuseTheSameValueInTheSameWords)
{
    for (const SceneSetting& s : sceneSettings()) {
        if (std::holds_alternative<bool>(s.defaultValue())) continue;
        const SettingValue bad = outOfRange(s);
        const std::string words = s.key + " " + *s.problem(bad);
        Scene scene = parseScene(kScene, "settings.toml");
        s.set(scene, bad);
        try {
            validateScene(scene);
            ADD_FAILURE() << s.key << ": validateScene accepted " << settingText(bad);
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
        // (A NaN in a file's array is refused by the reader's own words for arrays.)
        if (std::holds_alternative<Vec3>(bad)) continue;
        const std::string line = s.key + " = " + (s.key == "time_step" ? "-1.0" : settingText(bad));
        try {
            parseScene(withLine(s.section, line), "settings.toml");
            ADD_FAILURE() << s.key << ": the reader accepted " << line;
        } catch (const std::exception& e) {
            const std::string said = e.what();
            EXPECT_NE(said.find("settings.toml:"), std::string::npos) << said;
            EXPECT_NE(said.find(s.key + ": must be "), std::string::npos) << said;
        }
    }
}

// A setting that 0 leaves unset is written only when set, and a file that gives it 0 is told
// to leave it out.
TEST(SceneSettings, ZeroThatMeansUnsetIsLeftOutOfAFile)
{
    for (const SceneSetting& s : sceneSettings()) {
        if (s.form != SettingForm::OmittedWhenZero) continue;
        const std::string zero = std::holds_alternative<double>(s.defaultValue()) ? "0.0" : "0";
        try {
            parseScene(withLine(s.section, s.key + " = " + zero), "settings.toml");
            ADD_FAILURE() << s.key << " = 0 was accepted";
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find("leave it out"), std::string::npos) << e.what();
        }
        const Scene scene = parseScene(kScene, "settings.toml");
        if (s.key != "end_steps") {  // (kScene sets end_steps)
            EXPECT_EQ(sceneToToml(scene, ".").find(s.key + " ="), std::string::npos) << s.key;
        }
    }
}

// Each setting set to a value other than its default is written and reads back the same.
TEST(SceneSettings, EverySettingWrittenReadsBackTheSame)
{
    for (const SceneSetting& s : sceneSettings()) {
        Scene scene = parseScene(kScene, "settings.toml");
        if (s.key == "history_period") scene.output.historyEvery = 0;
        if (s.key == "safety") scene.timeStep.fixed = 0.0;  // safety goes with "auto"
        const SettingValue value = inRangeNotDefault(s);
        s.set(scene, value);
        const std::string text = sceneToToml(scene, ".");
        const Scene back = parseScene(text, "written.toml");
        EXPECT_EQ(settingText(s.get(back)), settingText(value)) << s.key << " in\n" << text;
        EXPECT_TRUE(s.get(back) == value) << s.key;
    }
}

// docs/scenes.md's [simulation] and [output] tables: a row for every setting of the section,
// and no other row but end_displacement (a table, not a setting); a setting given as its value
// shows its default as the schema's (a Scene's) default.
TEST(SceneSettings, ScenesMdTablesAgreeWithTheSchema)
{
    std::ifstream in(LSDEM_SOURCE_DIR "/docs/scenes.md");
    ASSERT_TRUE(in) << "docs/scenes.md not found";
    std::map<std::string, std::map<std::string, std::string>> rows;  // section → key → default
    std::string line, section;
    while (std::getline(in, line)) {
        if (line.rfind("## ", 0) == 0) {
            section.clear();
            for (const char* name : {"simulation", "output"})
                if (line.find("`[" + std::string(name) + "]`") != std::string::npos) section = name;
        }
        if (section.empty() || line.rfind("| `", 0) != 0) continue;
        const std::string cell = line.substr(3, line.find('`', 3) - 3);
        const std::string key = cell.substr(0, cell.find(' '));
        const size_t last = line.rfind(" | ");
        rows[section][key] = line.substr(last + 3, line.size() - last - 5);
    }
    ASSERT_EQ(rows.size(), 2u) << "no [simulation] or [output] table in docs/scenes.md";
    std::set<std::string> keys;
    for (const SceneSetting& s : sceneSettings()) {
        keys.insert(s.key);
        ASSERT_TRUE(rows[s.section].count(s.key))
            << s.key << " is not in docs/scenes.md's [" << s.section << "] table";
        if (s.form == SettingForm::Value) {
            EXPECT_EQ(rows[s.section][s.key], settingText(s.defaultValue())) << s.key;
        }
    }
    for (const auto& [name, table] : rows)
        for (const auto& [key, value] : table)
            EXPECT_TRUE(keys.count(key) || key == "end_displacement")
                << "docs/scenes.md lists '" << key << "' in [" << name
                << "], which the schema does not know";
}

// A material's density: the reader and validateScene refuse a negative one in the same words.
TEST(SceneSettings, DensityIsRefusedInTheSameWordsFromAFileAndAScene)
{
    const std::string words = "density " + *densityProblem(-1.0);
    EXPECT_EQ(words, "density must be >= 0 (got -1)");
    EXPECT_FALSE(densityProblem(0.0));
    EXPECT_TRUE(densityProblem(std::nan("")));
    std::string text = kScene;
    text.replace(text.find("density = 7.85e-9"), 17, "density = -1.0");
    try {
        parseScene(text, "settings.toml");
        ADD_FAILURE() << "the reader accepted a negative density";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("density: must be >= 0 (got -1)"), std::string::npos)
            << e.what();
    }
    Scene scene = parseScene(kScene, "settings.toml");
    scene.materials[0].density = -1.0;
    try {
        validateScene(scene);
        ADD_FAILURE() << "validateScene accepted a negative density";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}
