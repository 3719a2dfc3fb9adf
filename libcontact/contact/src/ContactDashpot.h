// The contact's dashpot (DampingModel.h applied to a contact; private to lsdem_contact): the
// contact seen as one body of springs (its axis), and the dashpot force on it.
#pragma once

#include "lsdem/contact/ContactLaw.h"

#include <vector>

namespace lsdem::contactlaw {

/// Where a contact is: the stiffness-weighted centre of its elastic point forces and their
/// stiffness-weighted mean direction, pushing first out of second (zero if it has none).
struct ContactPlace
{
    Vec3 centre = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
};

/// The place of the contact whose elastic point forces of the @a sideCount sides are
/// @a forces[s] (@a perNodeForces: one per contact, as NormalModel::perNodeForces says).
ContactPlace contactPlace(const ContactSide* sides, int sideCount,
                          const std::vector<PointForce>* forces, bool perNodeForces);

/// The contact seen as one body of springs: where it acts, along which normal, how stiff it is
/// along it and how fast its force grows with penetration. What its dashpot is made from.
struct ContactAxis
{
    Vec3 centre = Vec3::Zero();  ///< stiffness-weighted centre of the point forces
    Vec3 normal = Vec3::Zero();  ///< unit, pushing first out of second (zero: none)
    double stiffness = 0.0;      ///< Σ k_f·(n_f·n)²: the stiffness along the normal
    double force = 0.0;          ///< P: the elastic force along the normal (on first)
    double exponent = 1.0;       ///< d ln P / d ln δ ≈ δ_max·K/P (1 for a flat face)
};

/// The contact's dashpot (DampingModel.h): one force on first at the contact's centre along its
/// normal, against the approach (second gets the opposite), and each point force's share of
/// it, which counts as normal force in Coulomb's limit.
struct Dashpot
{
    double coefficient = 0.0;          ///< c (0: none)
    ContactAxis axis;
    Vec3 force = Vec3::Zero();         ///< on first
    /// Its normal force over Σ|F_n| of the point forces: a point force's share of it per unit
    /// of that force's own size, which counts in the force's Coulomb limit.
    double viscousPerForce = 0.0;
    double power = 0.0;                ///< what it dissipates: −force·(v_first − v_second) ≥ 0
};

/// The dashpot of the contact whose elastic point forces of the @a sideCount sides are
/// @a normal[s] (@a perNodeForces: one per contact, as NormalModel::perNodeForces says).
Dashpot contactDashpot(const ContactSide* sides, int sideCount, const ContactModel& model,
                       const std::vector<PointForce>* normal, bool perNodeForces);

} // namespace lsdem::contactlaw
