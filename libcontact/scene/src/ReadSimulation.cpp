// [simulation] and [output]: time stepping, the end condition and the outputs.
#include "SceneSections.h"

#include "lsdem/scene/SceneSettings.h"

namespace lsdem::scenefile {

namespace {

/// The settings of @a section (SceneSettings.h) that a file gives as plain values: each read
/// in its type and checked against its range. One that 0 would leave unset is given > 0 or
/// left out.
void readSettings(TableReader& t, const std::string& section, Scene& scene)
{
    for (const SceneSetting& s : sceneSettings()) {
        if (s.section != section || s.form == SettingForm::OwnForm || !t.has(s.key)) continue;
        SettingValue value = s.defaultValue();
        if (std::holds_alternative<double>(value)) value = t.number(s.key);
        if (std::holds_alternative<long long>(value)) value = t.integer(s.key);
        if (std::holds_alternative<bool>(value)) value = t.boolean(s.key, false);
        if (std::holds_alternative<Vec3>(value)) value = t.vec3(s.key);
        if (std::optional<std::string> p = s.problem(value)) t.fail(s.key, *p, s.fix);
        if (s.form == SettingForm::OmittedWhenZero && value == s.defaultValue())
            t.fail(s.key, "must be > 0 (got 0)", "leave it out: " + s.fix);
        s.set(scene, value);
    }
}

} // namespace

void readSimulation(const toml::table* table, Scene& scene)
{
    if (!table)
        throw Error(scene.path, "missing [simulation]",
                    "add [simulation] with at least an end condition (end_time, end_steps or "
                    "end_displacement)");
    TableReader t(*table, "[simulation]", scene.path);
    readSettings(t, "simulation", scene);
    if (t.has("time_step")) {
        const toml::node& n = t.node("time_step");
        if (n.is_string()) {
            if (n.as_string()->get() != "auto")
                t.fail("time_step", "unknown value '" + n.as_string()->get() + "'",
                       "write time_step = \"auto\" or a positive number");
        } else {
            scene.timeStep.fixed = t.positive("time_step");
        }
    }
    if (t.has("safety")) {
        if (scene.timeStep.fixed > 0.0)
            t.fail("safety", "only applies to time_step = \"auto\"", "remove it");
        const SceneSetting& safety = sceneSetting("safety");
        const double value = t.number("safety");
        if (std::optional<std::string> p = safety.problem(value)) t.fail("safety", *p, safety.fix);
        scene.timeStep.safety = value;
    }
    EndCondition& end = scene.end;
    if (t.has("end_displacement")) {
        const toml::node& n = t.node("end_displacement");
        if (!n.is_table())
            t.fail("end_displacement", "expected a table", "write end_displacement = { boundary = \"top\", value = 0.3 }");
        TableReader e(*n.as_table(), "[simulation] end_displacement", scene.path);
        end.boundary = lookUp(e, "boundary", scene.boundaries, "boundary",
                              "name a [[boundaries]] entry");
        end.displacement = e.positive("value");
        e.rejectUnknownKeys();
        // A servo wall moves too, at the speed its stress asks (the run measures the distance).
        const BoundarySpec& moved = scene.boundaries[static_cast<size_t>(end.boundary)];
        if (!(moved.velocity.norm() > 0.0) && !moved.servo.active())
            e.fail("boundary", "'" + moved.name +
                                   "' does not move, so it never reaches the displacement",
                   "give that boundary a velocity or a stress, or end by end_time / end_steps");
    }
    if (end.time <= 0.0 && end.steps <= 0 && end.boundary < 0)
        t.fail("", "has no end condition", "add end_time, end_steps or end_displacement");
    // A servo wall stops where its stress is met, maybe short of the displacement: the run
    // would never end.
    if (end.boundary >= 0 && scene.boundaries[static_cast<size_t>(end.boundary)].servo.active() &&
        end.time <= 0.0 && end.steps <= 0)
        t.fail("end_displacement",
               "names a servo wall, which stops where its stress is met and may never move "
               "that far",
               "add end_time or end_steps as well, as a limit");
    t.rejectUnknownKeys();
}

void readOutput(const toml::table* table, Scene& scene)
{
    if (!table) return;
    TableReader t(*table, "[output]", scene.path);
    if (t.has("history_every") && t.has("history_period"))
        t.fail("history_period", "both history_every and history_period are given", "keep one");
    readSettings(t, "output", scene);
    t.rejectUnknownKeys();
}

} // namespace lsdem::scenefile
