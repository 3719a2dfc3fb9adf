#include "lsdem/scene/SceneSettings.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <cmath>
#include <stdexcept>

namespace lsdem {

namespace {

// The get and set of the Scene's field FIELD, of type TYPE.
#define LSDEM_SETTING_FIELD(TYPE, FIELD)                                                        \
    [](const Scene& s) -> SettingValue { return s.FIELD; },                                     \
        [](Scene& s, const SettingValue& v) { s.FIELD = std::get<TYPE>(v); }

// Each entry: section, key, what it means, range, form in a file, the fix, get and set.

std::vector<SceneSetting> simulationSettings()
{
    return {
        {"simulation", "gravity", "Gravity (3,), length/time².", NumberRange::Finite,
         SettingForm::Value, "give three finite numbers, length/time²",
         LSDEM_SETTING_FIELD(Vec3, gravity)},
        {"simulation", "global_damping",
         "Non-viscous damping λ in [0, 1), as YADE's NewtonIntegrator; 0: none.",
         NumberRange::Fraction, SettingForm::Value, "0 means none; 0.1–0.3 settles grains",
         LSDEM_SETTING_FIELD(double, globalDamping)},
        // 0 in a Scene (and Python) is "auto" in a file.
        {"simulation", "time_step",
         "The fixed time step; 0 for automatic (safety times the stable step).",
         NumberRange::NonNegative, SettingForm::OwnForm,
         "give a step > 0, or \"auto\" (0 in Python)",
         LSDEM_SETTING_FIELD(double, timeStep.fixed)},
        {"simulation", "safety",
         "With the automatic step: the share of the stiffest contact's stable step taken.",
         NumberRange::PositiveFraction, SettingForm::OwnForm, "0.1–0.3 is usual",
         LSDEM_SETTING_FIELD(double, timeStep.safety)},
        {"simulation", "periodic_cell",
         "A periodic cell's period along x, y and z (0: not periodic along that axis), length; "
         "grains across a face touch the images of those at the other.",
         NumberRange::NonNegative, SettingForm::OmittedWhenDefault,
         "give each period ≥ 0 (0 for an axis that is not periodic), length",
         LSDEM_SETTING_FIELD(Vec3, periodicCell)},
        {"simulation", "periodic_origin", "The periodic cell's lowest corner (3,), length.",
         NumberRange::Finite, SettingForm::OmittedWhenDefault, "give three finite numbers, length",
         LSDEM_SETTING_FIELD(Vec3, periodicOrigin)},
        {"simulation", "periodic_strain_rate",
         "How fast the periodic cell stretches along each periodic axis, 1/time (< 0 "
         "compresses): the cell and the grains' positions in it deform affinely.",
         NumberRange::Finite, SettingForm::OmittedWhenDefault,
         "give three finite numbers, 1/time (0 along an axis that is not periodic)",
         LSDEM_SETTING_FIELD(Vec3, periodicStrainRate)},
        {"simulation", "periodic_stress",
         "Stress control of the periodic cell: the compressive stress each periodic axis is "
         "strained to reach, force/length² (0: that axis keeps periodic_strain_rate).",
         NumberRange::NonNegative, SettingForm::OmittedWhenDefault,
         "give each target ≥ 0 (0 for an axis the strain rate drives), force/length²",
         LSDEM_SETTING_FIELD(Vec3, periodicStress)},
        {"simulation", "periodic_max_strain_rate",
         "With periodic_stress: the fastest each stress-controlled axis strains, 1/time (at "
         "10 % off its target and beyond).",
         NumberRange::NonNegative, SettingForm::OmittedWhenDefault,
         "give each > 0 where periodic_stress is, 1/time",
         LSDEM_SETTING_FIELD(Vec3, periodicMaxStrainRate)},
        {"simulation", "end_time", "Stop at this simulated time (0: no time limit).",
         NumberRange::NonNegative, SettingForm::OmittedWhenZero, "0 for no time limit",
         LSDEM_SETTING_FIELD(double, end.time)},
        {"simulation", "end_steps", "Stop after this many steps (0: no step limit).",
         NumberRange::NonNegative, SettingForm::OmittedWhenZero, "0 for no step limit",
         LSDEM_SETTING_FIELD(long long, end.steps)},
    };
}

std::vector<SceneSetting> outputSettings()
{
    return {
        {"output", "history_every",
         "Steps between rows of energy.csv and boundary_<name>.csv (0: by history_period).",
         NumberRange::NonNegative, SettingForm::OmittedWhenZero,
         "steps between history rows; 0 to use history_period",
         LSDEM_SETTING_FIELD(long long, output.historyEvery)},
        {"output", "history_period",
         "Time between history rows (0: by history_every; neither: every 100 steps).",
         NumberRange::NonNegative, SettingForm::OmittedWhenZero,
         "time between history rows; 0 to use history_every",
         LSDEM_SETTING_FIELD(double, output.historyPeriod)},
        {"output", "vtk_period", "Time between ParaView frames (0: none).",
         NumberRange::NonNegative, SettingForm::Value, "0 for no frames",
         LSDEM_SETTING_FIELD(double, output.vtkPeriod)},
        {"output", "checkpoint_period",
         "Time between checkpoints (0: only at the end and on a signal).",
         NumberRange::NonNegative, SettingForm::Value,
         "0 for checkpoints only at the end and on a signal",
         LSDEM_SETTING_FIELD(double, output.checkpointPeriod)},
        {"output", "contact_forces", "Whether the ParaView frames hold the contact force points.",
         NumberRange::Finite, SettingForm::Value, "true or false",
         LSDEM_SETTING_FIELD(bool, output.contactForces)},
        {"output", "frame_spacing",
         "The spacing of each grain's surface in the ParaView frames, length (0: its asset's "
         "node spacing); coarser makes lighter frames of many grains.",
         NumberRange::NonNegative, SettingForm::OmittedWhenZero,
         "0 for the node spacing, or a length such as half a grain's radius",
         LSDEM_SETTING_FIELD(double, output.frameSpacing)},
        {"output", "micromechanics",
         "Whether the run writes micromechanics.csv: at each history row the sample's "
         "Love–Weber stress moment, its contact fabric and mechanical coordination.",
         NumberRange::Finite, SettingForm::Value, "true or false",
         LSDEM_SETTING_FIELD(bool, output.micromechanics)},
    };
}

#undef LSDEM_SETTING_FIELD

} // namespace

std::optional<std::string> SceneSetting::problem(const SettingValue& value) const
{
    if (value.index() != defaultValue().index()) return "has the wrong type";
    if (const double* d = std::get_if<double>(&value)) return outOfRange(range, *d);
    if (const long long* n = std::get_if<long long>(&value))
        return outOfRange(range, static_cast<double>(*n));
    if (const Vec3* v = std::get_if<Vec3>(&value)) {
        if (!(std::isfinite(v->x()) && std::isfinite(v->y()) && std::isfinite(v->z())))
            return "must be finite (got " + settingText(*v) + ")";
        for (int k = 0; k < 3; ++k)
            if (!inNumberRange(range, (*v)[k]))
                return "must be " + numberRangeText(range) + " in every component (got " +
                       settingText(*v) + ")";
        return std::nullopt;
    }
    return std::nullopt;  // a flag
}

SettingValue SceneSetting::defaultValue() const
{
    static const Scene defaults;
    return get(defaults);
}

bool SceneSetting::written(const Scene& scene) const
{
    const SettingValue value = get(scene);
    if (form == SettingForm::OmittedWhenDefault) return value != defaultValue();
    return std::holds_alternative<Vec3>(value) || std::holds_alternative<bool>(value) ||
           value != defaultValue();
}

const std::vector<SceneSetting>& sceneSettings()
{
    static const std::vector<SceneSetting> all = [] {
        std::vector<SceneSetting> v = simulationSettings();
        for (const SceneSetting& s : outputSettings()) v.push_back(s);
        return v;
    }();
    return all;
}

const SceneSetting& sceneSetting(const std::string& key)
{
    for (const SceneSetting& s : sceneSettings())
        if (s.key == key) return s;
    throw std::out_of_range("no scene setting named " + key);
}

void checkSetting(const SceneSetting& setting, const SettingValue& value, const std::string& where)
{
    if (std::optional<std::string> p = setting.problem(value))
        throw Error(where, setting.key + " " + *p, setting.fix);
}

std::string settingText(const SettingValue& value)
{
    if (const double* d = std::get_if<double>(&value)) return numberText(*d);
    if (const long long* n = std::get_if<long long>(&value)) return std::to_string(*n);
    if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
    const Vec3& v = std::get<Vec3>(value);
    return "[" + numberText(v.x()) + ", " + numberText(v.y()) + ", " + numberText(v.z()) + "]";
}

} // namespace lsdem
