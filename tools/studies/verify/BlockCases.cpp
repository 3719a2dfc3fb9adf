// Blocks on walls: a box sliding down an incline (a = g·(sin θ − μ·cos θ), or resting where
// tan θ < μ) and a box landing flat (the contact a whole face makes: the automatic time step
// must bear it, and its rebound is the restitution given, the face being a linear spring).
#include "studies/verify/ImpactTrace.h"
#include "studies/verify/RigidBodyTheory.h"
#include "studies/verify/VerifyCases.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"

#include <cmath>

namespace lsdem::verify {

namespace {

/// The issue's box: 10 × 10 × 4 mm, nodes 0.25 mm apart, voxel 0.1 mm, landing on a 10 × 10
/// face.
std::shared_ptr<const GrainAsset> issueBox(Context& c)
{
    return c.bodies.box(Vec3(10, 10, 4), c.quick ? 0.5 : 0.25, 0.1);
}

/// The laws a box's face applies: every one but the single-node law, whose one node of a
/// face's hundreds (all equally deep) is off the centre and tips the box.
std::vector<Formulation> faceLaws(const Context& c)
{
    return lawsOfCase(c, CaseLaws::Face);
}

} // namespace

void boxOnAnIncline(Context& c)
{
    const Setup& s = c.bodies.setup();
    const auto box = issueBox(c);
    const double friction = 0.3, time = c.quick ? 0.02 : 0.05;
    for (const Formulation f : lawsOfCase(c, CaseLaws::Frictional)) {
        for (const double degreesAngle : {30.0, 10.0}) {
            const double angle = degreesAngle * kPi / 180.0;
            const ContactModel law = lawFor(f, s, *box, friction, 0.3);
            Scene scene = caseScene(s, law);
            addGrain(scene, "box", box, Vec3(0, 0, 2.0));
            addWall(scene);
            // The incline is the floor with gravity turned by θ about y.
            scene.gravity = s.gravity * Vec3(std::sin(angle), 0, -std::cos(angle));
            World world = buildCase(scene);
            Simulation sim(std::move(world), automaticTimeStep(buildCase(scene), 0.2));
            // Least squares of v(t) over the second half (the first settles the face).
            double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
            while (sim.world().time < time) {
                sim.step();
                const double t = sim.world().time;
                if (t < 0.5 * time) continue;
                const double v = sim.world().grains[0].body.velocity.x();
                n += 1, st += t, sv += v, stt += t * t, stv += t * v;
            }
            const double measured = (n * stv - st * sv) / (n * stt - st * st);
            const double reference = inclineAcceleration(angle, friction, s.gravity);
            c.report.add({"incline " + numberText(degreesAngle) + "°", formulationName(f),
                          "acceleration down the slope", "mm/s²", reference, measured,
                          s.gravity * std::sin(angle), 0.01,
                          reference > 0.0 ? "rigid body: g·(sin θ − μ·cos θ); 1 % of g·sin θ"
                                          : "rigid body: rests where tan θ < μ; 1 % of g·sin θ"});
        }
    }
}

void boxLandingFlat(Context& c)
{
    const Setup& s = c.bodies.setup();
    const auto box = issueBox(c);
    const double speed = 1000.0, gap = 0.01;
    for (const Formulation f : faceLaws(c)) {
        // With the automatic step: it must land and leave again, the check passing throughout.
        {
            const ContactModel law = lawFor(f, s, *box, 0.0, 0.6);
            Scene scene = caseScene(s, law);
            addGrain(scene, "box", box, Vec3(0, 0, 2.0 + gap), Vec3(0, 0, -speed));
            addWall(scene);
            const double dt = automaticTimeStep(buildCase(scene), 0.2);
            Simulation sim(buildCase(scene), dt);
            double margin = 0.0;
            std::string failure;
            try {
                traceImpact(sim, [](const World&) { return 0.0; }, [](const World&) { return 0.0; },
                            1000000);
                margin = sim.stabilityLimitSeen() / dt;
            } catch (const Error& e) {
                failure = e.what();
            }
            // The automatic step is 0.2 of the stiffest face's limit with a partner as heavy
            // (stiffness doubled); on a wall, which does not move, the limit is √2 longer.
            c.report.add({"box-landing auto", formulationName(f),
                          "stability limit seen / automatic step", "", 5.0 * std::sqrt(2.0),
                          failure.empty() ? margin : 0.0, 5.0 * std::sqrt(2.0), 0.05,
                          failure.empty() ? "safety 0.2 of the face's limit, the partner's factor "
                                            "2 not used by a wall: 5·√2 (5 %: the edges)"
                                          : "the run stopped: " + failure});
        }
        // The rebound over restitutions, at a step that resolves the face's contact.
        for (const double e : {0.3, 0.6, 0.9}) {
            const ContactModel law = lawFor(f, s, *box, 0.0, e);
            Scene scene = caseScene(s, law);
            addGrain(scene, "box", box, Vec3(0, 0, 2.0 + gap), Vec3(0, 0, -speed));
            addWall(scene);
            World world = buildCase(scene);
            // The face: K = k*·(its area, 100 mm², and the edges' share); its half period
            // π·sqrt(m/K), resolved by 1000/e steps (as the ball's restitution sweep).
            const double mass = world.grains[0].body.mass;
            const double stiffness = tractionStiffness(law, *box) * 100.0;
            const double contact = kPi * std::sqrt(mass / stiffness);
            Simulation sim(std::move(world), contact / ((c.quick ? 400.0 : 1000.0) / e));
            traceImpact(sim, [](const World&) { return 0.0; }, [](const World&) { return 0.0; },
                        10000000);
            const double rebound = sim.world().grains[0].body.velocity.z() / speed;
            c.report.add({"box-landing e=" + numberText(e), formulationName(f),
                          "rebound / impact speed", "", e, rebound, e, 0.01,
                          "a face is a linear spring: the calibration for p = 1; 1 % (the goal)"});
        }
    }
}

} // namespace lsdem::verify
