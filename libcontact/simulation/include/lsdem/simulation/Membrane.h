/// @file Membrane.h
/// @brief A flexible membrane, as wraps the sample of a laboratory triaxial test: a
///        triangulated shell whose vertices are point masses, joined by constant-strain
///        membrane triangles (stretching only, no bending), loaded on its outer side by a
///        pressure that follows its surface. Grains touch it with their own nodes, tested
///        against its triangles as against a wall (MembraneContact.h), so every contact law
///        applies to it unchanged.
///
/// Why a shell and not bonded spheres: grains meet a smooth surface whose stiffness is the
/// rubber's (E·t, ν) by construction, not a calibration of bond springs, and the sample's
/// volume is that enclosed by the shell (divergence theorem). The shell need not be finer
/// than the grains: a node's force goes to its triangle's three vertices by barycentric
/// weights, so a coarse shell still carries every node's force.
///
/// The material is St Venant–Kirchhoff in plane stress (Green strain, so large rotations are
/// exact), with tension-field wrinkling: a membrane cannot carry compression, so a triangle
/// compressed across its stretch carries only the uniaxial stress E·e₁ along its largest
/// principal strain e₁, and nothing when e₁ ≤ 0 (a rubber membrane folds instead).
///
/// Units are the user's: E in force/area, t and positions in length, density in mass/volume
/// (a membrane's true mass makes the step tiny; a larger density is mass scaling, harmless in
/// a quasi-static test and reported by the step it allows).
#pragma once

#include "lsdem/core/Vec3.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace lsdem {

/// The rubber of a membrane.
struct MembraneMaterial
{
    double youngs = 0.0;     ///< E, force/area, > 0
    double poisson = 0.0;    ///< ν, in [0, 0.5)
    double thickness = 0.0;  ///< t, length, > 0
    double density = 0.0;    ///< mass/volume, > 0 (see the file's note on mass scaling)
};

/// One triangle's reference (unstretched) shape, in a 2-D frame of its own plane.
struct MembraneTriangle
{
    std::array<int, 3> vertices{};  ///< counter-clockwise seen from outside (normal outward)
    Eigen::Matrix2d inverseShape = Eigen::Matrix2d::Identity();  ///< of [e₁ e₂] in its frame
    double area = 0.0;                                           ///< reference area, > 0
};

struct Membrane
{
    std::string name;
    MembraneMaterial rubber;
    int material = 0;        ///< the contact material that grains meet it with
    double pressure = 0.0;   ///< on its outer side, pushing in (force/area); may change in a run
    /// Viscous drag on its free vertices, as the fluid of a triaxial cell gives: a traction
    /// −drag·v over each vertex's tributary area (force·time/length³; 0: none). Counted as
    /// damping in the energy balance.
    double drag = 0.0;
    /// The stress a controller (e.g. a triaxial study's) wants the grains to put on it; it
    /// steers the pressure towards it between steps. 0: none. The simulation does not read it.
    double targetStress = 0.0;

    std::vector<Vec3> positions, velocities;  ///< per vertex, world
    std::vector<double> masses;               ///< per vertex: a third of each triangle's
    /// Per vertex: the boundary whose motion it follows (a ring held by a platen), or -1: free.
    std::vector<int> heldBy;
    std::vector<MembraneTriangle> triangles;
    /// The directed edges that only one triangle has (the open rims, e.g. a tube's two ends),
    /// as that triangle runs them, and the rim each belongs to.
    std::vector<std::array<int, 2>> rimEdges;
    std::vector<int> rimOfEdge;
    int rimCount = 0;

    /// How far outside it a grain's node is still pushed back (length): beyond, a node has
    /// escaped (or lies across a thin sample). finishMembrane makes it a quarter of the mean edge.
    double contactReach = 0.0;

    /// Force on each vertex at the last evaluation (rubber, pressure and grains together) ...
    std::vector<Vec3> forces;
    /// ... and the grains' part of it (their push on the membrane; empty outside a Simulation),
    /// and the pressure's (whose power a Simulation books as boundary work; kept with the
    /// state, since the next step's work starts from it).
    std::vector<Vec3> grainForces, pressureForces;
    double strainEnergy = 0.0;  ///< at the last evaluation (force·length)
    /// The rubber's bound on ω² of its vertices at the last evaluation (membraneStableStep).
    double rubberOmegaSquared = 0.0;
    /// Energy the world's global damping took from its vertices so far (force·length).
    double dampedWork = 0.0;
};

/// Make the triangles' reference shapes and the vertices' masses from @a m's positions now
/// (taken as unstretched) and find its rims. @throw Error on a bad material or a degenerate or
/// inconsistently oriented triangle.
void finishMembrane(Membrane& m);

/// A tube: the side of a cylinder of @a radius and @a height whose axis runs from @a base
/// along unit @a axis, with @a segments vertices round each of @a rings + 1 rings; the
/// vertices start at rest and free, stretched round by @a prestretch (>= 1: its rubber's
/// unstretched radius is radius/prestretch). @throw Error on a non-positive size or a
/// prestretch below 1.
Membrane makeTubeMembrane(const Vec3& base, const Vec3& axis, double radius, double height,
                          int segments, int rings, const MembraneMaterial& rubber,
                          double prestretch = 1.0);

/// Set @a m.forces to the triangles' elastic forces plus the pressure's follower forces
/// (−p·a/3 on each vertex of a triangle of area vector a), @a m.strainEnergy and
/// @a m.rubberOmegaSquared. @a pressureForces, if given, receives the pressure's part alone.
void computeMembraneForces(Membrane& m, std::vector<Vec3>* pressureForces = nullptr);

/// The centroid of each of its rims' vertices, by rim (Membrane::rimOfEdge).
std::vector<Vec3> rimCentroids(const Membrane& m);

/// The volume the membrane encloses, its rims closed by flat fans to their centroids (the
/// platens a tube's ends are pressed against), by the divergence theorem: positive when its
/// triangles face outward.
double enclosedVolume(const Membrane& m);

/// Kinetic energy of its vertices.
double membraneKineticEnergy(const Membrane& m);

/// The rubber's and the pressure's bound on ω² of its vertices at its stretch now: the largest
/// of its triangles' lumped-mass eigenvalue bounds (1/time²).
double membraneRubberOmegaSquared(const Membrane& m);

/// The largest stable step of its vertices' explicit integration with the triangles'
/// stiffness, the pressure's and its drag (membraneRubberOmegaSquared with the drag's rate,
/// dampedStableStep), at its stretch now. The grains' contacts on it are checked at run time
/// (automaticTimeStep foresees the stiffest). Under global damping @a globalDamping
/// (λ), forces against the motion are 1 + λ times stronger, and the step shorter.
double membraneStableStep(const Membrane& m, double globalDamping = 0.0);

/// The drag's rate on a free vertex, c/m = drag/(density·thickness) (1/time): the same for
/// every vertex, whose drag and mass both follow its tributary area.
double membraneDragRate(const Membrane& m);

} // namespace lsdem
