/// @file StableStep.h
/// @brief How large a time step a grain's contacts allow, and the automatic time step.
///
/// Velocity Verlet on a spring of stiffness k and a body of mass m is stable for
/// dt < 2/ω, ω² = k/m; a dashpot at ratio β of critical lowers it to 2/ω·(sqrt(1 + β²) − β).
/// A grain in contact is a 6-degree-of-freedom body on many springs: with K_t the contacts'
/// translational stiffness (3×3) and K_r their rotational stiffness about its centroid, the
/// largest ω² of the grain is at most λ_max(K_t)/m + λ_max(I^-½ K_r I^-½) (I its inertia; the
/// largest eigenvalue of a positive semidefinite block matrix is at most the sum of its
/// diagonal blocks'), so that sum bounds the grain's fastest mode, the coupling of translation
/// and rotation by off-centre contacts included. Shear springs add k_t in the tangent plane.
#pragma once

#include "lsdem/simulation/RigidBody.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <vector>

namespace lsdem {

struct World;
struct Membrane;

/// A grain's contact stiffness and dashpots as the stability check sums them (PairForces,
/// SimulationForces.cpp): each contact scaled by 1 + m/m_partner for a partner that moves too.
/// Dashpots pressing a grain in parallel add up as their springs do: N equal contacts along
/// one direction damp the grain's mode at √N times each one's ratio, which a bound from one
/// contact's ratio misses (a ball between two walls at e = 0.2: the scheme amplifies beyond
/// ω·dt = 0.89, one contact's largest ratio allowed 1.02).
struct GrainStiffness
{
    Mat3 translation = Mat3::Zero();         ///< force/length, world
    Mat3 rotation = Mat3::Zero();            ///< moment/angle about the centroid, world
    Mat3 translationDamping = Mat3::Zero();  ///< Σ c·n nᵀ, force·time/length, world
    Mat3 rotationDamping = Mat3::Zero();     ///< Σ c·w wᵀ, moment·time/angle, world
};

/// How much stiffer and more viscous the contacts act for the step under global damping
/// @a globalDamping (λ, World::globalDamping): it makes every force against the motion 1 + λ
/// times stronger, so ω² and a dashpot's rate are 1 + λ times larger.
inline double globalDampingStiffening(double globalDamping)
{
    return 1.0 + std::max(0.0, globalDamping);
}

/// The largest stable step of an explicit oscillator of ω² @a omegaSquared (1/time²) damped at
/// the rate γ = c/m @a dampingRate (1/time, 2βω for a ratio β): 2/(sqrt(ω² + γ²/4) + γ/2),
/// which is 2/ω·(sqrt(1 + β²) − β); 2/γ without a spring, 2/ω without damping, infinite
/// without either. A dashpot evaluated from the velocity the step already has (the half
/// step's) is unstable beyond it, as a spring is beyond 2/ω. Under global damping
/// @a globalDamping (λ) the forces against the motion are 1 + λ times stronger: ω² and γ are
/// taken 1 + λ times larger (globalDampingStiffening). Inline: it runs for every grain at
/// every step.
inline double dampedStableStep(double omegaSquared, double dampingRate, double globalDamping = 0.0)
{
    const double boost = globalDampingStiffening(globalDamping);
    const double halfRate = 0.5 * boost * std::max(dampingRate, 0.0);
    const double root =
        std::sqrt(boost * std::max(omegaSquared, 0.0) + halfRate * halfRate) + halfRate;
    // (The sum, not sqrt(1 + β²) − β: no cancellation when the dashpot dominates.)
    return root > 0.0 ? 2.0 / root : std::numeric_limits<double>::infinity();
}

/// The largest stable step of @a body on springs @a stiffness with dashpots up to ratio
/// @a dampingRatio of critical (infinite without stiffness), under the world's global damping
/// @a globalDamping (λ, World::globalDamping), which makes forces against the motion 1 + λ
/// times stronger and so shortens the step. The damping rate is the larger of 2β·ω (each
/// contact's own ratio, on the fastest mode) and the bound on the summed dashpots' rate,
/// λ_max(C_t)/m + λ_max(I^-½ C_r I^-½), built as ω²'s is but with each λ_max bounded without
/// eigenvalues (the least of the Frobenius norm and Gershgorin's row sums: exact for dashpots
/// along the axes, at most √3 times over); the step is Verlet's limit
/// 2/(sqrt(ω² + γ²/4) + γ/2) for that ω and rate γ, which falls as either grows, so a bound on
/// each gives a bound on the step (exact where the dashpots and springs share their modes, as
/// contacts along their normals do).
double stableStep(const GrainStiffness& stiffness, const RigidBody& body, double dampingRatio,
                  double globalDamping = 0.0);

/// A cheap lower bound on stableStep (no eigenvalues: the springs' largest eigenvalue bounded
/// from the traces, Frobenius's norm and Gershgorin's row sums, whichever is least; the
/// dashpots' by Frobenius's norm; the smallest principal moment for the rotation's scaling),
/// within a factor f = 3^(1/4)·sqrt(I_max/I_min) of it for the springs (f² where the summed
/// dashpots' rate sets the step), exact for one frictionless contact on a sphere, and within a
/// hair of it for a sphere held alike on every side (as the grains of a packing are, where
/// Frobenius's norm alone was 3^(1/4) off). The simulation checks every grain at every step;
/// where this bound already clears the step and the least limit seen, the exact one cannot
/// change the outcome and is not computed.
double stableStepLowerBound(const GrainStiffness& stiffness, const RigidBody& body,
                            double dampingRatio, double globalDamping = 0.0);

/// The largest damping ratio β any contact model of @a world can give (ViscousDamping).
double largestDampingRatio(const World& world);

/// The band of a grain's surface that `time_step = "auto"` takes to be in contact: the nodes
/// within this fraction of its bounding radius of a flat wall (a sphere's cap at an overlap of
/// 1 % of its radius; the whole of a flat face).
constexpr double kAutomaticBandFraction = 0.01;

/// The automatic time step: safety · the stable step of the stiffest contact any free grain
/// can make. For each free grain, a flat wall is brought against its surface from many
/// directions (its principal axes and the level-set normals at up to 256 of its nodes, so
/// every flat face is met square): the nodes within kAutomaticBandFraction of its bounding
/// radius of the wall count, each with its normal and shear stiffness under every contact model
/// of the world, in translation and in rotation about the centroid, doubled for a partner
/// that moves as much (two equal free grains), with the largest damping ratio of the world.
/// Each membrane's vertices under the stiffest contact grains can make on one bound it too
/// (stiffestMembraneContactStep).
/// Deeper contacts, or many at once, are what the stability check at every step is for; the
/// safety factor (0.2 by default) leaves them 25 times the stiffness.
/// @throw Error if no free grain touches anything stiff (nothing to base a step on).
double automaticTimeStep(const World& world, double safety);

/// ω² (1/time²) of the stiffest contact the free grains of @a world can make on a free vertex
/// of membrane @a m (0 if every vertex is held): a flat face pressed over all of the vertex's
/// triangles gives it Σ w·k over the nodes there, the law's traction stiffness k* times the
/// vertex's lumped area, and its mass is density·thickness times that same area, so
/// ω² = k*/(density·thickness) whatever the mesh (the single-node law: its one spring on the
/// lightest vertex); doubled, as for grains, for a grain as heavy as the membrane under it
/// (the vertices' share 1 + m_m/M of the pair, MembraneContact.h). Crowded grains pressing a
/// fold with several times its area are what the safety factor leaves room for.
double stiffestMembraneContact(const World& world, const Membrane& m);

/// The stable step of membrane @a m's free vertices under that contact
/// (stiffestMembraneContact) with its dashpot (the world's largest ratio, on the pair's ω),
/// beside its rubber's ω² @a rubberOmegaSquared and its drag.
double stiffestMembraneContactStep(const World& world, const Membrane& m,
                                   double rubberOmegaSquared);

/// For each grain of @a world, the stable step of the stiffest contact it can make (what
/// automaticTimeStep takes the least of, at safety 1); infinite for a grain that is not free
/// or that no contact model gives any stiffness.
std::vector<double> stiffestContactSteps(const World& world);

} // namespace lsdem
