/// @file ContactLaw.h
/// @brief From penetrating nodes to forces: the normal law of the formulation, the per-node
///        shear springs with history, and a viscous dashpot on the contact's approach, applied
///        to one contact seen from one or two sides (one-way or symmetric node testing). Used
///        for grain–grain and grain–boundary contacts alike.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/contact/NodeContact.h"
#include "lsdem/contact/PointForce.h"
#include "lsdem/contact/ShearHistory.h"

#include <vector>

namespace lsdem {

/// A body as a contact sees it: a grain, or a boundary (asset may then be null).
struct ContactGrain
{
    const GrainAsset* asset = nullptr;
    RigidPose pose;
    /// Velocities over the step (velocity Verlet's half-step velocities): the relative
    /// displacement of the shear springs, the turn of their history, and the dashpot's rate.
    Vec3 velocity = Vec3::Zero();         ///< of the centroid (reference point), world
    Vec3 angularVelocity = Vec3::Zero();  ///< world
    int index = 0;                        ///< breaks one-way ties: the lower index tests
    double mass = 0.0;                    ///< for contact damping; 0: immovable

    /// Velocity of the material point at world point @a p.
    Vec3 pointVelocity(const Vec3& p) const
    {
        // v + ω × (p − c), written out by component: the same operations as Eigen's, but
        // kept in registers (Eigen's cross product goes through memory and then stalls the
        // vector addition that reads it back; this is on the contact law's hot path).
        const double rx = p.x() - pose.position.x(), ry = p.y() - pose.position.y(),
                     rz = p.z() - pose.position.z();
        const Vec3& w = angularVelocity;
        return Vec3(velocity.x() + (w.y() * rz - w.z() * ry),
                    velocity.y() + (w.z() * rx - w.x() * rz),
                    velocity.z() + (w.x() * ry - w.y() * rx));
    }
};

/// The nodes of @a tester found inside @a other, with the shear history of those nodes.
struct ContactSide
{
    const ContactGrain* tester = nullptr;
    const ContactGrain* other = nullptr;
    std::vector<NodeContact> contacts;   ///< in node order (as the narrow phase finds them)
    double weight = 1.0;                 ///< 1/2 per side in symmetric testing
    ShearHistory* history = nullptr;     ///< per-node shear; null: no shear carried over
};

/// Working memory of the contact laws, kept by each thread and reused from contact to
/// contact, so that computing a contact allocates nothing once the buffers have grown. Keep
/// one per thread in a ThreadPrivate (lsdem/core/ThreadPrivate.h).
struct ContactScratch
{
    std::vector<NodeContact> contacts[2];
    std::vector<PointForce> forces[2];
    std::vector<ShearHistory::Entry> nextHistory;
};

/// The result of one contact, for the two bodies it joins (first = the first side's tester).
struct PairForces
{
    Vec3 forceOnFirst = Vec3::Zero(), torqueOnFirst = Vec3::Zero();
    Vec3 forceOnSecond = Vec3::Zero(), torqueOnSecond = Vec3::Zero();
    int contactNodes = 0;       ///< penetrating nodes, all sides
    int pointForcesOnFirst = 0; ///< of the point forces appended, how many (leading) act on first
    /// The springs' energy: ½k·d² per node in contact (its mean over a patch; the volume
    /// law's own potential for its one force), plus ½|F_t|²/k_t per shear spring.
    double elasticEnergy = 0.0;
    /// How stiff the contact is for each body, for the stability check of the time step: in
    /// translation, Σ k_n·n nᵀ + k_t·(I − n nᵀ) over its point forces (the same for both
    /// bodies); in rotation about each body's centroid, Σ k_n·w wᵀ + k_t·[r×](I − n nᵀ)[r×]ᵀ
    /// with r the point's lever and w = r × n (zero for a body that cannot move).
    Mat3 translationalStiffness = Mat3::Zero();
    Mat3 rotationalStiffnessOfFirst = Mat3::Zero(), rotationalStiffnessOfSecond = Mat3::Zero();
    /// The contact's dashpot c (force·time/length) along its mean normal; 0 without damping.
    double dashpot = 0.0;
    /// The dashpot's moment arm about each body's centroid, w = r × n (r from the centroid to
    /// the contact's centre; zero for a body that cannot move): it resists that body's spin at
    /// c·w wᵀ, which the stability check sums beside the stiffness.
    Vec3 dashpotArmOfFirst = Vec3::Zero(), dashpotArmOfSecond = Vec3::Zero();
    /// Energy the contact dissipated over the step (force·length, ≥ 0; 0 when dt is 0): by
    /// friction, what the Coulomb caps took from the shear springs (updateShearForce) and what
    /// springs whose stiffness changed let go of (patch quadrature's, ks*·A_in); by the
    /// dashpot, its force against the bodies' approach times dt.
    double frictionWork = 0.0, dashpotWork = 0.0;
    /// Where the contact is, for micromechanics (Micromechanics.h): the stiffness-weighted
    /// centre of its elastic point forces and their mean direction, unit, pushing first out of
    /// second (both zero for a contact without nodes).
    Vec3 centre = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
};

/// Turn the sides of one contact into forces. The sides' testers must be the same two bodies
/// (side 0: first tests second; side 1, if any: second tests first). Each side's history is
/// replaced by the shear of the nodes now in contact. @a dt is the step over which the
/// relative motion slipped (0: no slip, and no friction work; the stored shear is still
/// carried onto the new tangent plane and capped).
///
/// The dashpot acts on the contact as a whole: on the two bodies' relative velocity at the
/// contact's stiffness-weighted centre, along its mean normal, with c = 2β·sqrt(m·K) for its
/// stiffness K along that normal and β calibrated for the contact's force–penetration
/// exponent (DampingModel.h); it pushes but never pulls (the normal force stays repulsive). So
/// it damps the approach of the bodies, and neither rolling nor sliding: a rolling sphere's
/// leading nodes approach the partner and its trailing nodes recede, which a dashpot per node
/// would turn into a resisting torque.
/// @param allForces if not null, receives each point force as it acts on its side's tester,
///                  the dashpot (node -1, at the contact's centre, on first) after side 0's
/// @param scratch   working memory to reuse (null: a temporary one)
PairForces resolveContact(ContactSide* sides, int sideCount, const ContactModel& model,
                          double dt, std::vector<PointForce>* allForces,
                          ContactScratch* scratch = nullptr);

} // namespace lsdem
