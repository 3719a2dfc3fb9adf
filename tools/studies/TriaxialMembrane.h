/// @file TriaxialMembrane.h
/// @brief The membrane triaxial's sample (--boundary membrane): a cylinder cut from the
///        sample consolidated between six walls, wrapped in a latex membrane (Membrane.h) at
///        the cell pressure, between the bottom and top walls as its platens.
///
/// Why cut from the walled sample: the grains are then already dense, and the membrane starts
/// snug round them (its radius the outermost grain's reach), so it need not shrink onto a loose
/// cloud; the grains outside the cylinder are dropped. The membrane's ends are held by the
/// platens (sealed to the end caps, as a laboratory's O-rings do: its pull acts on them) and its
/// rubber is latex's (E 1.4 MPa, ν 0.45), unless told half a grain thick: a laboratory's
/// membrane is about a grain thick on fine sand, and one as thin against the grains as the
/// laboratory's is against its sample (0.3 mm per 38 mm) wraps each grain instead of bridging
/// the voids (docs/triaxial.md#a-membrane-instead-of-side-walls). Its density is raised until
/// its vertices are stable at the grains' step (mass scaling: a quasi-static test is
/// indifferent to it; the run says how heavy it is against the grains), and the cell's fluid
/// drags on it, so that it closes in on the grains at a pace instead of falling onto them.
#pragma once

#include "studies/TriaxialCell.h"
#include "studies/TriaxialOptions.h"

#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

namespace lsdem {

struct TriaxialMembraneSample
{
    World world;          ///< the cut grains, the two platens (boundaries 0 and 1), the membrane
    TriaxialWalls walls;  ///< platens 0 (bottom) and 1 (top), membrane 0
    long long grainsCut = 0;  ///< dropped: outside the cylinder
    double radius = 0.0;      ///< the membrane's, mm
    double massRatio = 0.0;   ///< the membrane's mass over the grains'
    /// The index in the consolidated sample of each grain kept, in the world's order.
    std::vector<long long> kept;
    /// The membrane as a scene's tube makes it (material, hold and state left to the caller).
    MembraneSpec tube;
};

/// Cut and wrap @a consolidated (in the cell of @a walls, six planes). @a meanDiameter (mm) sets
/// the membrane's triangles (half a diameter across); @a dt the step it must be stable at;
/// @a stiffnessPerArea the grain–wall law's normal stiffness per unit area (kn*, or kn over the
/// nodes' mean area), which its vertices feel from the grains; @a strainRate the shearing's
/// (1/s), which sets the cell fluid's drag on the membrane. @throw Error if no grain fits in
/// the cylinder.
TriaxialMembraneSample wrapInMembrane(const World& consolidated, const TriaxialWalls& walls,
                                      const TriaxialOptions& o, double meanDiameter, double dt,
                                      double stiffnessPerArea, double strainRate);

} // namespace lsdem
