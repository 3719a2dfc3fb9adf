// The oblique and spin impact cases' shared runs and references (ObliqueImpact.h).
#include "studies/verify/ObliqueImpact.h"

#include "studies/verify/ImpactTrace.h"
#include "studies/verify/NormalImpactReference.h"

#include "lsdem/core/Constants.h"

#include <cmath>
#include <cstdio>

namespace lsdem::verify {

/// The laws of @a c that carry shear springs.
std::vector<Formulation> frictionalLaws(const Context& c)
{
    return lawsOfCase(c, CaseLaws::Frictional);
}

std::string degrees(double radians)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.0f°", radians * 180.0 / kPi);
    return text;
}

/// The steps of an impact at normal speed @a normalSpeed: a thousandth of the contact time of
/// the adapted law's continuum limit (powerLawImpact), whatever the tangential motion.
double impactStep(const Setup& s, double mass, double normalSpeed, bool quick)
{
    const NormalImpact n = powerLawImpact(kPi * s.knStar * s.radius, 2.0, mass, normalSpeed);
    return n.contactTime / (quick ? 400.0 : 1000.0);
}

/// A ball of the setup thrown at a wall (normal +z), or with @a partnerRadius at a ball of
/// that radius below it (Chung & Ooi test 8: 1000 times as dense, so 125,000 times as heavy
/// at five times the radius; taken as immovable: lsdem's spherical boundary, whose distance is
/// exact), with velocity @a v and spin @a w, under @a law: its state once it has left.
Rebound ballOnWall(Context& c, const ContactModel& law, const Vec3& v, const Vec3& w,
                   double partnerRadius)
{
    const Setup& s = c.bodies.setup();
    const auto ball = c.bodies.sphere();
    Scene scene = caseScene(s, law);
    addGrain(scene, "ball", ball, Vec3(0, 0, s.radius * 1.001), v, w);
    if (partnerRadius > 0.0) {
        BoundarySpec b;
        b.name = "heavy_ball";  // names a file, were it written: no space
        b.shape = BoundaryShape::Sphere;
        b.material = 1;
        b.center = Vec3(0, 0, -partnerRadius);
        b.radius = partnerRadius;
        scene.boundaries.push_back(b);
    } else {
        addWall(scene);
    }
    World world = buildCase(scene);
    const double dt = impactStep(s, world.grains[0].body.mass, -v.z(), c.quick);
    Simulation sim(std::move(world), dt);
    const ImpactTrace t = traceImpact(
        sim, [&](const World& wd) { return s.radius - wd.grains[0].body.pose.position.z(); },
        [](const World&) { return 0.0; }, 100000);
    const Grain& g = sim.world().grains[0];
    return {g.body.velocity, g.angularVelocity(), t.maxOverlap};
}

WallReferences wallReferences(Context& c, const ContactModel& law, double mass, const Vec3& v,
                              const Vec3& w, double partnerRadius)
{
    Surface surface;
    surface.radius = partnerRadius;
    const Setup& s = c.bodies.setup();
    const auto ball = c.bodies.sphere();
    const double inertia = 0.4 * mass * s.radius * s.radius;
    const double height = s.radius * 1.001;
    const double step = impactStep(s, mass, -v.z(), c.quick) / 5.0;
    WallReferences r;
    r.nodes = ballOnSurface(nodesOf(*ball), law, mass, inertia, surface, height, v, w, step);
    if (law.normal().stiffnessPerArea()) {
        // A lattice 30 points across the largest cap's radius (from the undamped normal
        // impact), over the cap and as far again as the ball can turn in the contact.
        const NormalImpact n = powerLawImpact(kPi * s.knStar * s.radius, 2.0, mass, -v.z());
        const double cap = std::sqrt(2.0 * s.radius * n.maxOverlap);
        const double turn = (w.norm() + 5.0 * law.friction * 2.0 * -v.z() / s.radius) * n.contactTime;
        const double spacing = cap / (c.quick ? 15.0 : 30.0);
        r.continuum = ballOnSurface(lowerCap(s.radius, 1.3 * cap / s.radius + turn, spacing), law,
                                    mass, inertia, surface, height, v, w, step);
        r.hasContinuum = true;
    }
    return r;
}

ImpactBody ballBody(double mass, double radius, const Vec3& v, const Vec3& w, const Vec3& lever)
{
    ImpactBody b;
    b.mass = mass;
    b.inertia = 0.4 * mass * radius * radius;
    b.velocity = v;
    b.angularVelocity = w;
    b.lever = lever;
    return b;
}

ImpactBody wallBody()
{
    ImpactBody wall;
    wall.movable = false;
    return wall;
}

double ballMass(Context& c)
{
    const Setup& s = c.bodies.setup();
    return s.density * 4.0 / 3.0 * kPi * std::pow(s.radius, 3);
}

/// Whether rigid-body theory slides throughout with margin: the slip, 3.5·μ·(1+e)·V_n to stop,
/// is at least 1/0.8 times that (near the threshold, the springs' compliance decides).
bool clearlySliding(double slip, double normalSpeed, double friction, double restitution)
{
    return std::abs(slip) * 0.8 >= 3.5 * friction * (1.0 + restitution) * normalSpeed;
}

/// Add the checks of a quantity against the node reference and the continuum.
void addThreeWay(Context& c, const std::string& name, Formulation f, const std::string& quantity,
                 const std::string& unit, double value, double nodes, double continuum,
                 bool hasContinuum, double scale)
{
    c.report.add({name, formulationName(f), quantity, unit, nodes, value, scale, kNodeTolerance,
                  "the law on these nodes, point by point; steps"});
    if (hasContinuum)
        c.report.add({name, formulationName(f), quantity + " (continuum)", unit, continuum, value,
                      scale, kLatticeTolerance, "the law's continuum limit: node quadrature"});
}

} // namespace lsdem::verify
