/// @file SlabModel.h
/// @brief The physical model of the slab study: the blocks' stiffnesses, the contact model,
///        the baked block and the time step.
///
/// Physical model (defaults, see SlabMaterial): blocks of soda-lime glass, E = 70 GPa,
/// ν = 0.22, ρ = 2.5e-9 t/mm³, μ = 0.4. The adapted normal stiffness is the elastic-foundation
/// modulus of a block loaded over a face: a traction p compresses a block of length L by
/// p·L/E, so kn* = E/L (traction per penetration; 8.75e3 N/mm³ for L = 8 mm), and
/// ks* = kn*/(2(1 + ν)) (the same with G for E). The original formulation gets a per-node
/// stiffness that matches the adapted one at a reference spacing s_ref:
/// kn = kn*·(√3/2)·s_ref² (a node's area on an equilateral mesh of edge s_ref), so the two
/// agree there and part as the surface is refined. The frame and the indenter are rigid and
/// touch the blocks with the same law. Damping: contact restitution 0.5 and YADE's global
/// damping 0.3 (quasi-static loading), gravity on.
#pragma once

#include "studies/SlabOptions.h"

#include "lsdem/contact/ContactModel.h"
#include "lsdem/ls/GrainAsset.h"

#include <memory>

namespace lsdem {

/// The resolved stiffnesses (N and mm) of a study.
struct SlabStiffness
{
    double knStar = 0.0, ksStar = 0.0;   ///< adapted (and volume), N/mm³
    double kn = 0.0, ks = 0.0;           ///< original (and single-node), N/mm
};

/// The stiffnesses the study uses, with defaults filled in (see the file comment).
SlabStiffness slabStiffness(const SlabStudyOptions& o);

/// The contact model of blocks with each other, the frame and the indenter.
ContactModel slabContactModel(const SlabStudyOptions& o, Formulation formulation);

/// Bake the panel's one block shape: level set at @a vdp, nodes by isotropic remeshing at
/// @a sdp (sharp edges kept), areas from the mesh.
std::shared_ptr<const GrainAsset> bakeSlabBlock(const SlabPanel& panel, double vdp, double sdp);

/// dt = safety·2·sqrt(m/K), K the stiffness of the stiffest expected contact: a block pressed
/// between its two x neighbours, 2·kn*·A_shared (adapted), 2·kn·N_shared (original, N_shared
/// the nodes on a shared face).
double slabTimeStep(const SlabStudyOptions& o, const SlabPanel& panel, const GrainAsset& block,
                    Formulation formulation);

} // namespace lsdem
