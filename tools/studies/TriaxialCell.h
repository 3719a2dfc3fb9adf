/// @file TriaxialCell.h
/// @brief What a triaxial test measures on a cuboid cell of six plane walls: the cell's size,
///        the principal stresses from the walls' forces over their current areas, p and q,
///        axial and volumetric strain from a reference size, the void ratio and the
///        coordination number. Compression is positive (soil mechanics); the axis of loading
///        is z. Units are the scene's (e.g. mm, N: stresses in N/mm² = MPa).
#pragma once

#include "lsdem/simulation/Simulation.h"
#include "lsdem/simulation/World.h"

#include <array>
#include <vector>

namespace lsdem {

/// The boundary indices of the six walls, each a plane whose normal points into the cell:
/// x min, x max, y min, y max, z min (bottom), z max (top). Or none: a periodic cell
/// (PeriodicCell.h, periodic along all three axes) bounds the sample, its size and stress the
/// cell's. Or a membrane (Membrane.h, the world's membrane of index @a membrane) round a
/// cylindrical sample between the bottom and top walls (the platens), the four side walls none:
/// the cell pressure σ₃ is its pressure.
struct TriaxialWalls
{
    std::array<int, 6> index = {-1, -1, -1, -1, -1, -1};
    bool periodic = false;
    int membrane = -1;

    bool hasMembrane() const { return membrane >= 0; }
};

/// The sample in the world's periodic cell: no walls.
inline TriaxialWalls periodicTriaxialCell()
{
    TriaxialWalls w;
    w.periodic = true;
    return w;
}

/// Wall @a which (0 to 5, in TriaxialWalls' order) of the cell in @a w.
inline Boundary& wallOf(World& w, const TriaxialWalls& walls, int which)
{
    return w.boundaries[size_t(walls.index[size_t(which)])];
}

/// The two other pairs of walls around the walls of @a axis (0 x, 1 y, 2 z): the rectangle
/// between them is the area those walls push on (StressServo::areaWalls).
std::array<int, 4> areaWallsOf(const TriaxialWalls& walls, int axis);

struct TriaxialState
{
    /// Edge lengths along x, y, z (distances between walls); in a membrane, the platens'
    /// distance along z and across, the side of the square of the sample's mean cross-section
    /// (volume / height), so that size.prod() is its volume.
    Vec3 size = Vec3::Zero();
    double volume = 0.0;          ///< size.x · size.y · size.z
    /// σ_x, σ_y, σ_z: each the mean of its two walls' normal force over their current area; in
    /// a membrane, σ_x = σ_y the grains' radial push on it over the side of the sample's mean
    /// cylinder (the cell pressure less the rubber's own hold, which a laboratory corrects
    /// for: here it is measured) and σ_z the platens' mean force (the grains' and the
    /// membrane's pull on its rims, as a load cell reads it) over the mean cross-section.
    Vec3 stress = Vec3::Zero();
    double p = 0.0;               ///< mean stress (σ_x + σ_y + σ_z) / 3
    double q = 0.0;               ///< deviator σ_z − (σ_x + σ_y) / 2
    double voidRatio = 0.0;       ///< (volume − solid volume) / solid volume
    double coordination = 0.0;    ///< mean grain–grain contacts per grain, 2C/N
    // From the contacts themselves (Micromechanics.h), when they are given:
    /// The Love–Weber stress's normal components over the cell's volume, compression positive
    /// as `stress` is: the grains' own measure of what the walls measure.
    Vec3 loveWeberStress = Vec3::Zero();
    double mechanicalCoordination = 0.0;  ///< rattlers out (Thornton)
    double fabricAnisotropy = 0.0;        ///< of the grain contacts' normals
    double nodesPerContact = 0.0;         ///< mean penetrating nodes of a grain–grain contact
};

/// The cell of @a world bounded by @a walls (plane boundaries, checked: @throw Error naming
/// the wall if one is not a plane, not facing into the cell, or opposite walls not parallel
/// and facing each other). @a contacts: the contacts of the last evaluation
/// (Simulation::contactRecords; empty leaves the coordination and what comes from contacts 0).
TriaxialState measureTriaxialCell(const World& world, const TriaxialWalls& walls,
                                  const std::vector<ContactRecord>& contacts);

/// Move the pressure of the membrane of @a walls by @a gain times what the grains' lateral
/// stress lacks of its target stress (Membrane::targetStress; none: nothing), kept from half to
/// three times the target.
void steerMembranePressure(World& world, const TriaxialWalls& walls, double gain);

/// The mean cross-section (volume / height) of the sample in the membrane of @a walls.
double membraneSampleArea(const World& world, const TriaxialWalls& walls);

/// The grains' solid volume: Σ of their assets' volumes.
double solidVolume(const World& world);

/// Axial strain (H₀ − H)/H₀ along z and volumetric strain (V₀ − V)/V₀ from the reference
/// state @a start (compression positive, so dilation is negative).
double axialStrain(const TriaxialState& start, const TriaxialState& now);
double volumetricStrain(const TriaxialState& start, const TriaxialState& now);

/// The mobilised friction angle (degrees) of an axisymmetric state, from Mohr–Coulomb:
/// sin φ = |σ_z − σ_r|/(σ_z + σ_r) with σ_r the mean lateral stress (so compression and
/// extension alike).
double mobilisedFrictionAngle(const TriaxialState& state);
/// The same from the largest and smallest of the three principal stresses (a true triaxial
/// state, σ₁ > σ₂ > σ₃).
double principalFrictionAngle(const TriaxialState& state);

} // namespace lsdem
