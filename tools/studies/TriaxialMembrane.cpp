#include "studies/TriaxialMembrane.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

namespace {

/// The membrane's hoop stretch round the sample as it is put on.
constexpr double kPrestretch = 1.05;

/// How many times the shearing's strain rate the membrane, pushed by σ₃ alone, would move in
/// the cell fluid (as a strain rate of its radius).
constexpr double kDragRate = 20.0;

/// Where plane wall @a b of the cell is now.
Vec3 wallPoint(const Boundary& b)
{
    return b.plane.point + b.displacement;
}

/// The membrane's density that keeps its vertices stable at step @a dt: its rubber and
/// pressure at half their limit (membraneStableStep grows as √density), and the grains
/// pressing on a vertex at a quarter of theirs. A vertex of tributary area A holds mass
/// density·t·A; grains pressing on all of it with stiffness per area k would give
/// ω² = k/(density·t), but grains crowding a fold of the membrane press on it with several
/// times its area (2.4-4.1 times, measured on 400 sand grains with triangles half a grain
/// across): hence the quarter.
double stableDensity(const Membrane& m, double dt, double stiffnessPerArea)
{
    // (m is at density 1: its masses are per unit density.)
    const double atUnitDensity = membraneStableStep(m);
    const double forRubber = std::pow(dt / (0.5 * atUnitDensity), 2.0);
    const double forContacts = stiffnessPerArea * std::pow(dt / (0.25 * 2.0), 2.0) / m.rubber.thickness;
    return std::max(forRubber, forContacts);
}

} // namespace

TriaxialMembraneSample wrapInMembrane(const World& consolidated, const TriaxialWalls& walls,
                                      const TriaxialOptions& o, double meanDiameter, double dt,
                                      double stiffnessPerArea, double strainRate)
{
    const Boundary& x0 = consolidated.boundaries[size_t(walls.index[0])];
    const Boundary& x1 = consolidated.boundaries[size_t(walls.index[1])];
    const Boundary& y0 = consolidated.boundaries[size_t(walls.index[2])];
    const Boundary& y1 = consolidated.boundaries[size_t(walls.index[3])];
    const Boundary& bottom = consolidated.boundaries[size_t(walls.index[4])];
    const Boundary& top = consolidated.boundaries[size_t(walls.index[5])];
    const double xLow = wallPoint(x0).x(), xHigh = wallPoint(x1).x();
    const double yLow = wallPoint(y0).y(), yHigh = wallPoint(y1).y();
    const double zLow = wallPoint(bottom).z(), zHigh = wallPoint(top).z();
    const double cx = 0.5 * (xLow + xHigh), cy = 0.5 * (yLow + yHigh);
    const double cut = 0.5 * std::min(xHigh - xLow, yHigh - yLow);

    TriaxialMembraneSample sample;
    World& w = sample.world;
    w = consolidated;
    w.grains.clear();
    double radius = 0.0, grainMass = 0.0;
    for (size_t i = 0; i < consolidated.grains.size(); ++i) {
        const Grain& g = consolidated.grains[i];
        const Vec3& c = g.body.pose.position;
        const double reach = std::hypot(c.x() - cx, c.y() - cy) + g.asset->boundingRadius;
        if (reach > cut) {
            ++sample.grainsCut;
            continue;
        }
        sample.kept.push_back(static_cast<long long>(i));
        radius = std::max(radius, reach);
        grainMass += g.body.mass;
        w.grains.push_back(g);
    }
    if (w.grains.empty())
        throw Error("triaxial membrane", "no grain lies wholly inside the cylinder cut from the "
                                         "consolidated sample",
                    "use more grains (--grains)");
    // The grains renumbered and the side walls gone: the contacts start afresh (the
    // consolidation is frictionless, so no shear is lost with them).
    w.pairHistory.clear();
    w.boundaryHistory.clear();
    w.boundaries = {bottom, top};
    for (Boundary& b : w.boundaries) {
        b.velocity = Vec3::Zero();
        b.servo = StressServo();
    }
    w.energy = EnergyBook();

    MembraneMaterial rubber;
    rubber.youngs = o.membraneYoungs;
    rubber.poisson = 0.45;
    rubber.thickness = o.membraneThickness > 0.0 ? o.membraneThickness : 0.5 * meanDiameter;
    rubber.density = 1.0;
    // Triangles a third of a grain across; the rubber stretched 5 % round the grains (a
    // laboratory's membrane is a little narrower than its sample), so it is taut from the start
    // and stays so while the sample consolidates (a slack membrane has no stiffness at all).
    const double edge = meanDiameter / 3.0, height = zHigh - zLow;
    const int segments = std::max(12, int(std::ceil(2.0 * kPi * radius / edge)));
    const int rings = std::max(2, int(std::ceil(height / edge)));
    Membrane m = makeTubeMembrane(Vec3(cx, cy, zLow), Vec3::UnitZ(), radius, height, segments,
                                  rings, rubber, kPrestretch);
    m.name = "membrane";
    m.pressure = o.confiningStress;
    m.rubber.density = stableDensity(m, dt, stiffnessPerArea);
    // (Its reference shapes stay the unstretched tube's: finishMembrane would take the
    // stretched one as unstretched. Only its masses change with the density.)
    for (double& mass : m.masses) mass *= m.rubber.density;
    for (int i = 0; i < segments; ++i) {
        m.heldBy[size_t(i)] = 0;                        // the bottom ring, by the bottom platen
        m.heldBy[size_t(rings * segments + i)] = 1;     // the top ring, by the top platen
    }
    // The cell fluid's drag: unsupported, the membrane would move in at kDragRate times the
    // shearing's strain rate times R (σ₃ = drag·v); bulging as the sample is sheared, at about
    // half the strain rate times R, it is held back by about σ₃/40, which the pressure's
    // steering makes up for (the grains' lateral stress is measured, not assumed).
    m.drag = o.confiningStress / (kDragRate * strainRate * radius);
    m.material = bottom.material;  // the grains meet it as they meet the walls
    double membraneMass = 0.0;
    for (double mass : m.masses) membraneMass += mass;
    w.membranes = {m};
    MembraneSpec& tube = sample.tube;
    tube.name = m.name;
    tube.rubber = m.rubber;
    tube.pressure = m.pressure;
    tube.drag = m.drag;
    tube.base = Vec3(cx, cy, zLow);
    tube.axis = Vec3::UnitZ();
    tube.radius = radius;
    tube.height = height;
    tube.segments = segments;
    tube.rings = rings;
    tube.prestretch = kPrestretch;

    sample.walls.index = {-1, -1, -1, -1, 0, 1};
    sample.walls.membrane = 0;
    sample.radius = radius;
    sample.massRatio = membraneMass / grainMass;
    return sample;
}

} // namespace lsdem
