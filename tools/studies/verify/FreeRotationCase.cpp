// A box spinning about its intermediate principal axis, in free space: it turns over and back
// (the tennis racket), its spin about that axis changing sign every 2K(k)/λ (Jacobi's elliptic
// solution, FreeRotationReference.h), with energy and angular momentum conserved.
#include "studies/verify/FreeRotationReference.h"
#include "studies/verify/VerifyCases.h"

#include "lsdem/simulation/Simulation.h"

#include <cmath>

namespace lsdem::verify {

void freeRotation(Context& c)
{
    const Setup& s = c.bodies.setup();
    const auto box = c.bodies.box(Vec3(10, 6, 4), 0.5, 0.2);
    Scene scene = caseScene(s, lawFor(Formulation::Adapted, s, *box, 0.0, 1.0));
    const double spin = 100.0;  // rad/s about the intermediate axis, y
    const Vec3 omega(0.01 * spin, spin, 0.01 * spin);
    addGrain(scene, "box", box, Vec3::Zero(), Vec3::Zero(), omega);
    World world = buildCase(scene);
    const RigidBody start = world.grains[0].body;
    const Vec3 moments = start.principalInertia;
    const double flip = intermediateAxisFlipTime(moments, omega);
    const int flips = c.quick ? 2 : 4;
    const double dt = flip / (c.quick ? 5000.0 : 20000.0);
    Simulation sim(std::move(world), dt);
    const double energy0 = start.kineticEnergy(), momentum0 = start.angularMomentum.norm();
    double worstEnergy = 0.0, worstMomentum = 0.0;
    std::vector<double> crossings;
    double previous = omega.y();
    Series trace;
    trace.name = "free_rotation";
    trace.columns = {"time", "omega1", "omega2", "omega3"};
    while (int(crossings.size()) < flips + 1 && sim.world().time < (flips + 2) * flip) {
        sim.step();
        const RigidBody& b = sim.world().grains[0].body;
        const Vec3 body = b.pose.orientation.conjugate() * b.angularVelocity();
        if ((previous > 0.0) != (body.y() > 0.0)) {
            const double t = sim.world().time;
            crossings.push_back(t - dt + previous / (previous - body.y()) * dt);
        }
        previous = body.y();
        worstEnergy = std::max(worstEnergy, std::abs(b.kineticEnergy() / energy0 - 1.0));
        worstMomentum = std::max(worstMomentum, std::abs(b.angularMomentum.norm() / momentum0 - 1.0));
        if (sim.world().step % 20 == 0) trace.rows.push_back({sim.world().time, body.x(), body.y(), body.z()});
    }
    const double measured = crossings.size() >= 2
                                ? (crossings.back() - crossings.front()) / double(crossings.size() - 1)
                                : 0.0;
    c.report.add({"free-rotation", "-", "time between flips", "s", flip, measured, flip, 1e-3,
                  "Jacobi: 2K(k)/λ; the splitting's phase error O((ω·dt)²)"});
    c.report.add({"free-rotation", "-", "largest energy change", "", 0.0, worstEnergy, 1.0, 1e-6,
                  "conserved; the splitting keeps it to O((ω·dt)²)"});
    c.report.add({"free-rotation", "-", "largest change of |L|", "", 0.0, worstMomentum, 1.0,
                  1e-15 * double(sim.world().step),
                  "conserved to round-off (1e-15 a step): exact rotations about principal axes"});
    c.report.series.push_back(trace);
}

} // namespace lsdem::verify
