// [simulation] and [output]: time stepping, the end condition and the outputs.
#include "SceneSections.h"

namespace lsdem::scenefile {

void readSimulation(const toml::table* table, Scene& scene)
{
    if (!table)
        throw Error(scene.path, "missing [simulation]",
                    "add [simulation] with at least an end condition (end_time, end_steps or "
                    "end_displacement)");
    TableReader t(*table, "[simulation]", scene.path);
    scene.gravity = t.vec3("gravity", Vec3::Zero());
    scene.globalDamping = t.number("global_damping", 0.0);
    if (!(scene.globalDamping >= 0.0 && scene.globalDamping < 1.0))
        t.fail("global_damping", "must be in [0, 1)", "0 means none; 0.1–0.3 settles grains");
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
        scene.timeStep.safety = t.positive("safety");
        if (scene.timeStep.safety > 1.0)
            t.fail("safety", "must be in (0, 1]", "0.1–0.3 is usual");
    }
    EndCondition& end = scene.end;
    if (t.has("end_time")) end.time = t.positive("end_time");
    if (t.has("end_steps")) end.steps = t.positiveInteger("end_steps");
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
    OutputSpec& o = scene.output;
    if (t.has("history_every") && t.has("history_period"))
        t.fail("history_period", "both history_every and history_period are given", "keep one");
    if (t.has("history_every")) o.historyEvery = t.positiveInteger("history_every");
    if (t.has("history_period")) o.historyPeriod = t.positive("history_period");
    o.vtkPeriod = t.nonNegative("vtk_period", 0.0);
    o.checkpointPeriod = t.nonNegative("checkpoint_period", 0.0);
    o.contactForces = t.boolean("contact_forces", true);
    t.rejectUnknownKeys();
}

} // namespace lsdem::scenefile
