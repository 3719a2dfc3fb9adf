/// @file Micromechanics.h
/// @brief What granular mechanics measures inside a sample, from its contacts: the Love–Weber
///        stress (of the sample and of each grain), the fabric of the contact normals and its
///        deviatoric anisotropy, and the mechanical coordination number with rattlers left out.
///
/// Free grains are the sample; a fixed or prescribed grain acts as a boundary (its contacts
/// with free grains count as boundary contacts). Units are the scene's: a stress moment is
/// force·length, a stress force/length² (compression negative, as in continuum mechanics).
#pragma once

#include "lsdem/simulation/Simulation.h"
#include "lsdem/simulation/World.h"

#include <vector>

namespace lsdem {

struct Micromechanics
{
    /// Σ over the free grains p and their contacts c of (x_c − x_p) ⊗ f_c, f_c the force on p:
    /// the Love–Weber stress of the sample times its volume (divide by the sample's volume,
    /// grains and voids, for the stress). In static equilibrium it is symmetric, and for a
    /// sample between walls it equals Σ over the wall contacts of x_c ⊗ f_c.
    Mat3 stressMoment = Mat3::Zero();
    /// (1/C) Σ n ⊗ n over the C contacts between free grains (trace 1; I/3 if isotropic).
    Mat3 fabric = Mat3::Zero();
    /// sqrt(3/2 · a:a) of the deviatoric fabric a = 15/2 · (fabric − I/3) (Satake; Rothenburg
    /// & Bathurst): 0 for isotropic normals.
    double fabricAnisotropy = 0.0;
    /// (1/C) Σ l̂ ⊗ l̂ over the same contacts, l̂ the unit branch vector between the two grains'
    /// centroids (for round grains the normal's fabric; elongated grains tilt one from the
    /// other), and its anisotropy as above.
    Mat3 branchFabric = Mat3::Zero();
    double branchAnisotropy = 0.0;
    /// Σ f_n n ⊗ n / Σ f_n over the same contacts, f_n = |f·n| the normal force: the normals'
    /// fabric weighted by how hard each contact presses (trace 1), and its anisotropy as above,
    /// which adds the forces' own anisotropy to the normals' (a_c + a_n of Ouadfel &
    /// Rothenburg, to first order).
    Mat3 forceFabric = Mat3::Zero();
    double forceAnisotropy = 0.0;
    double meanNormalForce = 0.0;    ///< Σ f_n / C
    long long grainContacts = 0;     ///< C: contacts between free grains
    long long boundaryContacts = 0;  ///< contacts of free grains with boundaries and fixed grains
    int freeGrains = 0;              ///< N
    /// Free grains with no grain contact (N0) or one (N1): they carry no stress (rattlers).
    int rattlers = 0;
    /// Thornton's mechanical coordination number (2C − N1)/(N − N0 − N1) (0 if every grain
    /// rattles).
    double mechanicalCoordination = 0.0;
};

/// The sample's micromechanics from the contacts @a records of @a world (Simulation::
/// contactRecords), summed in the records' order.
Micromechanics micromechanicsOf(const World& world, const std::vector<ContactRecord>& records);

/// Each grain's Love–Weber stress (1/V_p) Σ_c (x_c − x_p) ⊗ f_c, V_p its volume, by grain index
/// (zero for a grain that is not free).
std::vector<Mat3> grainStresses(const World& world, const std::vector<ContactRecord>& records);

} // namespace lsdem
