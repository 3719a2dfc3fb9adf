#include "studies/TriaxialCell.h"

#include "lsdem/simulation/Micromechanics.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lsdem {

namespace {

const char* const kWallNames[6] = {"x min", "x max", "y min", "y max", "z min", "z max"};

const Boundary& wall(const World& world, const TriaxialWalls& walls, int which)
{
    const int index = walls.index[size_t(which)];
    if (index < 0 || index >= static_cast<int>(world.boundaries.size()))
        throw Error("triaxial cell", std::string("the ") + kWallNames[which] +
                                         " wall is not one of the scene's boundaries",
                    "give the index of a plane boundary");
    const Boundary& b = world.boundaries[size_t(index)];
    if (b.shape != BoundaryShape::Plane)
        throw Error("triaxial cell", "wall '" + b.name + "' (" + kWallNames[which] +
                                         ") is not a plane",
                    "bound the cell with six planes");
    return b;
}

/// The platens' distance and their mean compressive force: the cell's size and stress along z
/// (@a stress still to be divided by the area).
void measureAxis(const World& world, const TriaxialWalls& walls, int axis, double& size,
                 double& force)
{
    const Boundary& low = wall(world, walls, 2 * axis);
    const Boundary& high = wall(world, walls, 2 * axis + 1);
    const Vec3 n = low.plane.normal;
    // Opposite walls: parallel, facing each other, the low one's normal along +axis.
    if (n.dot(high.plane.normal) > -1.0 + 1e-9 || n[axis] < 1.0 - 1e-9)
        throw Error("triaxial cell",
                    "walls '" + low.name + "' and '" + high.name + "' are not a pair of "
                    "opposite planes facing into the cell along " + "xyz"[axis],
                    "use planes with normals +e and -e of that axis");
    const Vec3 lowPoint = low.plane.point + low.displacement;
    const Vec3 highPoint = high.plane.point + high.displacement;
    size = (highPoint - lowPoint).dot(n);
    // The grains push a wall against its normal: compression is -F·n.
    force = 0.5 * (-low.force.dot(n) - high.force.dot(high.plane.normal));
}

/// The cell's size and principal stresses from @a walls' positions and forces.
void measureWalls(const World& world, const TriaxialWalls& walls, TriaxialState& s)
{
    double force[3];
    for (int axis = 0; axis < 3; ++axis) measureAxis(world, walls, axis, s.size[axis], force[axis]);
    const double volume = s.size.prod();
    for (int axis = 0; axis < 3; ++axis) {
        const double area = volume / s.size[axis];
        s.stress[axis] = force[axis] / area;
    }
}

/// A cylindrical sample in a membrane between two platens (walls 4 and 5). Its lateral stress
/// is what the grains put on the membrane: the radial part of their push on its vertices over
/// the side of the sample's mean cylinder (2π·R·H, π·R²·H its volume); before any evaluation,
/// the membrane's pressure.
void measureMembrane(const World& world, const TriaxialWalls& walls, TriaxialState& s)
{
    if (walls.membrane >= static_cast<int>(world.membranes.size()))
        throw Error("triaxial cell", "the world has no membrane " + std::to_string(walls.membrane));
    const Membrane& m = world.membranes[size_t(walls.membrane)];
    double height = 0.0, force = 0.0;
    measureAxis(world, walls, 2, height, force);
    const double volume = enclosedVolume(m);
    const double side = std::sqrt(volume / height);
    double lateral = m.pressure;
    if (m.grainForces.size() == m.positions.size()) {
        Vec3 axis = Vec3::Zero();  // a point of the sample's axis: the vertices' mean
        for (const Vec3& x : m.positions) axis += x;
        axis /= static_cast<double>(m.positions.size());
        double radialForce = 0.0;
        for (size_t i = 0; i < m.positions.size(); ++i) {
            const Vec3 out(m.positions[i].x() - axis.x(), m.positions[i].y() - axis.y(), 0.0);
            if (out.norm() > 0.0) radialForce += m.grainForces[i].dot(out.normalized());
        }
        const double radius = std::sqrt(volume / (kPi * height));
        lateral = radialForce / (2.0 * kPi * radius * height);
    }
    s.size = Vec3(side, side, height);
    s.stress = Vec3(lateral, lateral, force / (side * side));
}
} // namespace

void steerMembranePressure(World& world, const TriaxialWalls& walls, double gain)
{
    Membrane& m = world.membranes[size_t(walls.membrane)];
    if (!(m.targetStress > 0.0)) return;
    TriaxialState s;
    measureMembrane(world, walls, s);
    // From half to three times the target: the rubber's hold on a sample ten grains across is
    // a correction of up to half of σ₃ (measured: 5 % on 182 grains, 50 % on 27 with a membrane
    // a grain thick), and a membrane still closing in on the grains measures no stress at all
    // (steered by that alone, its pressure would wind up).
    m.pressure = std::clamp(m.pressure + gain * (m.targetStress - s.stress.x()),
                            0.5 * m.targetStress, 3.0 * m.targetStress);
}

double membraneSampleArea(const World& world, const TriaxialWalls& walls)
{
    TriaxialState s;
    measureMembrane(world, walls, s);
    return s.size.x() * s.size.y();
}

TriaxialState measureTriaxialCell(const World& world, const TriaxialWalls& walls,
                                  const std::vector<ContactRecord>& contacts)
{
    TriaxialState s;
    if (walls.periodic) {
        if (!(world.periodic.size.minCoeff() > 0.0))
            throw Error("triaxial cell", "the world has no periodic cell along every axis",
                        "give the scene periodic_cell = [Lx, Ly, Lz]");
        s.size = world.periodic.size;
        s.stress = world.periodic.stress;  // the contacts' Love–Weber stress, as the cell measures it
    } else if (walls.hasMembrane()) {
        measureMembrane(world, walls, s);
    } else {
        measureWalls(world, walls, s);
    }
    s.volume = s.size.prod();
    s.p = s.stress.sum() / 3.0;
    s.q = s.stress.z() - 0.5 * (s.stress.x() + s.stress.y());
    const double solid = solidVolume(world);
    s.voidRatio = solid > 0.0 ? (s.volume - solid) / solid : 0.0;
    if (contacts.empty() || world.grains.empty()) return s;
    long long pairs = 0, nodes = 0;
    for (const ContactRecord& c : contacts)
        if (c.second >= 0) ++pairs, nodes += c.nodes;
    s.coordination = 2.0 * double(pairs) / double(world.grains.size());
    s.nodesPerContact = pairs > 0 ? double(nodes) / double(pairs) : 0.0;
    const Micromechanics m = micromechanicsOf(world, contacts);
    s.loveWeberStress = -m.stressMoment.diagonal() / s.volume;
    s.mechanicalCoordination = m.mechanicalCoordination;
    s.fabricAnisotropy = m.fabricAnisotropy;
    return s;
}

std::array<int, 4> areaWallsOf(const TriaxialWalls& walls, int axis)
{
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    return {walls.index[size_t(2 * u)], walls.index[size_t(2 * u + 1)],
            walls.index[size_t(2 * v)], walls.index[size_t(2 * v + 1)]};
}

double solidVolume(const World& world)
{
    double volume = 0.0;
    for (const Grain& g : world.grains) volume += g.asset->mass.volume;
    return volume;
}

double axialStrain(const TriaxialState& start, const TriaxialState& now)
{
    return (start.size.z() - now.size.z()) / start.size.z();
}

double volumetricStrain(const TriaxialState& start, const TriaxialState& now)
{
    return (start.volume - now.volume) / start.volume;
}

double mobilisedFrictionAngle(const TriaxialState& state)
{
    const double axial = state.stress.z();
    const double lateral = 0.5 * (state.stress.x() + state.stress.y());
    if (!(axial + lateral > 0.0)) return 0.0;
    return std::asin(std::clamp(std::abs(axial - lateral) / (axial + lateral), 0.0, 1.0)) * 180.0 /
           kPi;
}

double principalFrictionAngle(const TriaxialState& state)
{
    const double major = state.stress.maxCoeff(), minor = state.stress.minCoeff();
    if (!(major + minor > 0.0)) return 0.0;
    return std::asin(std::clamp((major - minor) / (major + minor), 0.0, 1.0)) * 180.0 / kPi;
}

} // namespace lsdem
