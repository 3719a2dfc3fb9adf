/// @file TangentialModel.h
/// @brief The tangential sub-model: a linear shear spring per contact node, with history. The
///        stored shear force is carried along with the contact (turned onto the current
///        tangent plane, and about the normal by the pair's mean spin, keeping its size, so it
///        is objective: a pair turning as one rigid body keeps its shear in its own frame),
///        incremented by -k_t·Δu_t and capped by Coulomb's μ·|F_n| (the node's normal force:
///        its spring and its share of the contact's dashpot). Its stiffness follows the
///        normal law's rule: ks per node (original) or ks*·A_a per area (adapted).
#pragma once

#include "lsdem/contact/NormalModel.h"
#include "lsdem/core/Vec3.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

/// The spring's step. Inline: it runs for every node in contact at every step, and a call
/// would pass its vectors through memory. At most two square roots.
/// @param stored   shear force from the last step (zero for a node just entering contact)
/// @param normal   current unit contact normal
/// @param slip     relative displacement of the contact point in the step (any direction;
///                 only its tangential part counts)
/// @param twist    the angle the pair turned about @a normal in the step: (ω_A + ω_B)/2 · n·dt
/// @param stiffness k_t of this node (force/length)
/// @param limit    μ·|F_n|, the largest shear the node can carry
/// @param dissipated if not null, gains the energy friction took in the step (≥ 0): the work of
///                 the force the bodies felt along the slip, less the spring's energy gained,
///                 for a force held at a cap that moves linearly from the stored force to the
///                 new limit: (|trial| − |capped|)·(|capped| + min(|stored|, |trial|))/(2·k_t).
///                 Exact for a node sliding along its stored force whatever its normal force
///                 does (μ·|F_n| times the slip at a steady one; the spring's lost energy where
///                 the limit fell without slip); for slip across the stored force it is off by
///                 a term of second order in the angle between them; at the step a sticking
///                 node starts to slide it counts (|trial| − cap)·(cap − |stored|)/(2·k_t) too
///                 little, once.
/// @return the new shear force (tangent to @a normal, at most @a limit long; zero if
///         @a limit ≤ 0)
inline Vec3 updateShearForce(const Vec3& stored, const Vec3& normal, const Vec3& slip,
                             double twist, double stiffness, double limit,
                             double* dissipated = nullptr)
{
    // Carry the stored force with the contact without changing its size: onto the new tangent
    // plane (the normal's own turn), then about the normal by the pair's mean spin (which a
    // projection cannot see). A turning contact must neither create nor destroy shear. The
    // small-angle turn s + θ·n×s is brought back to |stored| below, with the projection's
    // rescaling (|stored| / |turned| as one root): exact in size, second order in angle.
    Vec3 shear = stored - stored.dot(normal) * normal;
    shear += twist * normal.cross(shear);
    const double before2 = stored.squaredNorm(), after2 = shear.squaredNorm();
    if (after2 > 0.0) shear *= std::sqrt(before2 / after2);
    const Vec3 tangentialSlip = slip - slip.dot(normal) * normal;
    shear -= stiffness * tangentialSlip;
    const double size2 = shear.squaredNorm();
    if (limit < 0.0 || size2 > limit * limit) {  // sliding: Coulomb cap
        const double trial = std::sqrt(size2), capped = limit > 0.0 ? limit : 0.0;
        shear *= (limit > 0.0 ? limit / trial : 0.0);
        if (dissipated)
            *dissipated += (trial - capped) * 0.5 * (capped + std::min(std::sqrt(before2), trial)) /
                           stiffness;
    }
    return shear;
}

/// Shear springs with Coulomb friction, for the formulations with per-node forces.
struct ShearSpringModel
{
    double stiffness = 0.0;  ///< ks (force/length) or ks* (force/length³), per the normal law
    double friction = 0.0;   ///< Coulomb coefficient μ

    /// Whether shear forces arise at all with normal law @a normal: it needs per-node forces,
    /// a stiffness and friction.
    bool active(const NormalModel& normal) const
    {
        return normal.perNodeForces() && stiffness > 0.0 && friction > 0.0;
    }
    /// k_t of a node of tributary area @a area, at testing weight @a weight.
    double nodeStiffness(const NormalModel& normal, double area, double weight) const
    {
        return nodeStiffness(normal.stiffnessPerArea(), area, weight);
    }
    /// The same, for a normal law whose stiffnessPerArea() is @a perArea (asked once, not per
    /// node).
    double nodeStiffness(bool perArea, double area, double weight) const
    {
        return weight * NormalModel::nodeStiffness(perArea, stiffness, area);
    }
};

} // namespace lsdem
