/// @file SceneSettings.h
/// @brief The schema of a scene's settings, the single values of its [simulation] and [output]
///        sections: each key's type, range, default (the Scene's own) and the fix for a value
///        out of range. The scene reader, validateScene, the scene writer, the Python builder
///        (one property per setting) and docs/scenes.md's tables share it, so a rule is written
///        once. A new setting is one entry here (and a field of Scene).
#pragma once

#include "lsdem/core/NumberRange.h"
#include "lsdem/scene/Scene.h"

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace lsdem {

/// A setting's value: a number, a count, a flag or a vector.
using SettingValue = std::variant<double, long long, bool, Vec3>;

/// How a file gives a setting.
enum class SettingForm {
    Value,            ///< as its value
    OmittedWhenZero,  ///< 0 means "not given" (an end condition): > 0, or left out
    /// Any value in range; a written scene gives it only where it is not the default (a
    /// vector that most scenes leave at zero: the periodic cell).
    OmittedWhenDefault,
    /// In a form of its own that its section's code reads and writes (time_step = "auto",
    /// safety only with it); checked and offered to Python like the rest.
    OwnForm,
};

struct SceneSetting
{
    std::string section;  ///< "simulation" or "output"
    std::string key;      ///< as the file and Python name it
    std::string doc;      ///< what it means, in a line (Python's docstring)
    /// What its numbers may be in a Scene (a vector's components: finite; a flag: anything).
    NumberRange range;
    SettingForm form;     ///< how a file gives it
    std::string fix;  ///< the advice when a value is out of range
    SettingValue (*get)(const Scene&);
    /// Set on @a scene a value of this setting's type already in range.
    void (*set)(Scene&, const SettingValue&);

    /// "must be in [0, 1) (got 2)" if @a value is out of range (or of the wrong type).
    std::optional<std::string> problem(const SettingValue& value) const;
    /// Its value in a default Scene.
    SettingValue defaultValue() const;
    /// Whether a written scene must give it: always for a vector and a flag (the file says what
    /// it holds), otherwise when it differs from the default.
    bool written(const Scene& scene) const;
};

/// Every setting, section by section in the order a scene writes them.
const std::vector<SceneSetting>& sceneSettings();

/// The setting @a key. @throw std::out_of_range if there is none (a program error).
const SceneSetting& sceneSetting(const std::string& key);

/// Throws lsdem::Error at @a where ("[simulation]", "scene.toml: [output]") if @a value is out
/// of @a setting's range: "global_damping must be in [0, 1) (got 2)", with the fix.
void checkSetting(const SceneSetting& setting, const SettingValue& value, const std::string& where);

/// A setting's value as text, as a file writes it ("0.2", "[0, 0, -9810]", "true").
std::string settingText(const SettingValue& value);

} // namespace lsdem
