// The cases again on the ball's nodes refined, 1000 → 16,000 (voxels refined with them, at 0.4
// of the node spacing, the paper's VDP/SDP): the adapted law's errors against its continuum
// limits must shrink. The quantities: a ball's normal impact on a wall and on a ball (peak force
// and contact time), its rebound at e = 0.5, an oblique impact at 10° where the slip stops (the
// tangential restitution), and rolling (the apparent resistance).
#include "studies/verify/ImpactTrace.h"
#include "studies/verify/NormalImpactReference.h"
#include "studies/verify/RollingRun.h"
#include "studies/verify/ShearFieldReference.h"
#include "studies/verify/VerifyCases.h"

#include "lsdem/contact/SphereContactReference.h"
#include "lsdem/core/Constants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lsdem::verify {

namespace {

constexpr double kImpactSpeed = 3900.0;

struct Errors
{
    double wallForce = 0, wallTime = 0, pairForce = 0, pairTime = 0, restitution = 0;
    double obliqueRestitution = 0, rollingResistance = 0;
};

Errors errorsAt(Context& c, int nodes, double ballMass)
{
    const Setup& s = c.bodies.setup();
    const double radius = s.radius, v = kImpactSpeed, gap = 1e-3 * radius;
    const double spacing = std::sqrt(4.0 * kPi * radius * radius / nodes);
    const auto ball = c.bodies.sphere(radius, nodes, 0.4 * spacing);
    const ContactModel elastic = lawFor(Formulation::Adapted, s, *ball, 0.0, 1.0);
    const auto quiet = [](const World&) { return 0.0; };
    Errors e;
    {  // A ball on a wall: P = π·k*·R·δ².
        const NormalImpact limit = powerLawImpact(kPi * s.knStar * radius, 2.0, ballMass, v);
        Scene scene = caseScene(s, elastic);
        addGrain(scene, "ball", ball, Vec3(0, 0, radius + gap), Vec3(0, 0, -v));
        addWall(scene);
        Simulation sim(buildCase(scene), limit.contactTime / 1000.0);
        const ImpactTrace t = traceImpact(
            sim, quiet, [](const World& w) { return -w.boundaries[0].force.z(); }, 20000);
        e.wallForce = t.peakForce / limit.peakForce - 1.0;
        e.wallTime = t.contactTime / limit.contactTime - 1.0;
    }
    {  // Two balls: the exact cap integral.
        const auto force = [&](double d) { return exactSphereContactForce(radius, d, s.knStar); };
        const NormalImpact limit = forceLawImpact(force, 0.5 * ballMass, v, 0.1 * radius);
        Scene scene = caseScene(s, elastic);
        addGrain(scene, "ball", ball, Vec3(-radius - 0.5 * gap, 0, 0), Vec3(0.5 * v, 0, 0));
        addGrain(scene, "ball", ball, Vec3(radius + 0.5 * gap, 0, 0), Vec3(-0.5 * v, 0, 0));
        Simulation sim(buildCase(scene), limit.contactTime / 1000.0);
        const ImpactTrace t = traceImpact(
            sim, quiet, [](const World& w) { return -w.grains[0].force.x(); }, 20000);
        e.pairForce = t.peakForce / limit.peakForce - 1.0;
        e.pairTime = t.contactTime / limit.contactTime - 1.0;
    }
    {  // The rebound at e = 0.5, 2000 steps a contact (as the restitution sweep).
        const NormalImpact limit = powerLawImpact(kPi * s.knStar * radius, 2.0, ballMass, v);
        Scene scene = caseScene(s, lawFor(Formulation::Adapted, s, *ball, 0.0, 0.5));
        addGrain(scene, "ball", ball, Vec3(0, 0, radius + gap), Vec3(0, 0, -v));
        addWall(scene);
        Simulation sim(buildCase(scene), limit.contactTime / 2000.0);
        traceImpact(sim, quiet, quiet, 200000);
        e.restitution = sim.world().grains[0].body.velocity.z() / v / 0.5 - 1.0;
    }
    {  // 10° from the normal, μ 0.092, e 0.98: the slip stops; against the continuum.
        const ContactModel law = lawFor(Formulation::Adapted, s, *ball, 0.092, 0.98);
        const double angle = 10.0 * kPi / 180.0;
        const Vec3 velocity(v * std::sin(angle), 0, -v * std::cos(angle));
        Scene scene = caseScene(s, law);
        addGrain(scene, "ball", ball, Vec3(0, 0, radius * 1.001), velocity);
        addWall(scene);
        const NormalImpact n = powerLawImpact(kPi * s.knStar * radius, 2.0, ballMass, -velocity.z());
        Simulation sim(buildCase(scene), n.contactTime / 1000.0);
        traceImpact(sim, quiet, quiet, 100000);
        const double cap = std::sqrt(2.0 * radius * n.maxOverlap);
        const BallImpact limit = ballOnSurface(
            lowerCap(radius, 1.3 * cap / radius + 0.1, cap / 30.0), law, ballMass,
            0.4 * ballMass * radius * radius, Surface(), radius * 1.001, velocity, Vec3::Zero(),
            n.contactTime / 5000.0);
        e.obliqueRestitution =
            (sim.world().grains[0].body.velocity.x() - limit.velocity.x()) / velocity.x();
    }
    {  // Rolling under its own weight, e 0.3: the apparent resistance.
        const RollingRun run = slideAndRoll(c, ball, Formulation::Adapted, 1000.0, 0.3, 0.3,
                                            c.quick ? 0.05 : 0.1);
        e.rollingResistance = 1.4 * run.deceleration / s.gravity;
    }
    return e;
}

} // namespace

void convergence(Context& c)
{
    const Setup& s = c.bodies.setup();
    const double ballMass = s.density * 4.0 / 3.0 * kPi * std::pow(s.radius, 3);
    const std::vector<int> counts = c.quick ? std::vector<int>{1000, 16000}
                                            : std::vector<int>{1000, 2000, 4000, 8000, 16000};
    std::vector<Errors> errors;
    Series table;
    table.name = "convergence";
    table.columns = {"nodes", "wall peak force", "wall contact time", "pair peak force",
                     "pair contact time", "rebound at e 0.5", "oblique 10° restitution",
                     "rolling resistance"};
    for (const int n : counts) {
        errors.push_back(errorsAt(c, n, ballMass));
        const Errors& e = errors.back();
        table.rows.push_back({double(n), e.wallForce, e.wallTime, e.pairForce, e.pairTime,
                              e.restitution, e.obliqueRestitution, e.rollingResistance});
    }
    c.report.series.push_back(table);
    // Each error at the finest count: at most half the larger of the two coarsest (of the
    // counts before it), or within a floor (the steps' and the level set's own error, 0.3 %; for
    // rolling, the goal μ_r 0.002). The errors of one count scatter with its node pattern, so
    // the check is against the coarsest two, not the next.
    const struct { const char* name; double Errors::*field; double floor; } quantities[] = {
        {"wall peak force", &Errors::wallForce, 3e-3},
        {"wall contact time", &Errors::wallTime, 3e-3},
        {"pair peak force", &Errors::pairForce, 3e-3},
        {"pair contact time", &Errors::pairTime, 3e-3},
        {"rebound at e 0.5", &Errors::restitution, 3e-3},
        {"oblique 10° restitution", &Errors::obliqueRestitution, 3e-3},
        {"rolling resistance μ_r", &Errors::rollingResistance, 2e-3}};
    for (const auto& q : quantities) {
        const size_t coarsest = std::min<size_t>(2, errors.size() - 1);
        double coarse = 0.0;
        for (size_t k = 0; k < coarsest; ++k) coarse = std::max(coarse, std::abs(errors[k].*q.field));
        const double fine = std::abs(errors.back().*q.field);
        char label[48];
        std::snprintf(label, sizeof label, "convergence N=%d", counts.back());
        c.report.add({label, "adapted", std::string(q.name) + " |error|", "", 0.0, fine, 1.0,
                      std::max(0.5 * coarse, q.floor),
                      "refined nodes: the error falls to half the coarsest (or to the floor)"});
    }
}

} // namespace lsdem::verify
