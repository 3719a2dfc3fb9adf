/// @file StressServo.h
/// @brief A plane wall that keeps a target normal stress: a servo moves it along its normal so
///        that the grains' force on it, over its current area, tends to the target. The law is
///        the usual one of PFC and YADE (proportional, with a gain from the contact stiffness
///        and the time step, and a limit speed):
///
///            v = clamp(α·(σ_target − σ)·A / (K·Δt + C), −v_max, v_max)   along its normal,
///
///        σ = −F·n / A the measured stress (F: the grains' force on the wall, n: its normal
///        towards the grains; compression positive), A its area, K = Σ k n·n of its contacts
///        at the last force evaluation (force/length), C the sum of their viscous dashpots
///        (force·time/length; 0 without contact damping) and α in (0, 1] the fraction of the
///        stress error the wall would close in one step if the grains did not move: moving at v
///        for a step changes the force by K·v·Δt + C·v. (Without C, a dashpot much stiffer
///        than K·Δt would make the wall flip between ±v_max.) Without contacts the wall moves
///        at ±v_max. The velocity depends only on the state (forces, K, C, positions), so a
///        restart continues bit for bit.
#pragma once

#include "lsdem/contact/RigidPose.h"

#include <array>

namespace lsdem {

struct World;
struct Boundary;

struct StressServo
{
    double targetStress = 0.0;  ///< > 0 (compressive, force/length²); 0: no servo
    /// The area the stress acts on: a fixed value (> 0) ...
    double area = 0.0;
    /// ... or the rectangle between two pairs of opposite walls (boundary indices, each pair
    /// perpendicular to this wall), at their current positions: |(p_b − p_a)·n_a| · |...|.
    std::array<int, 4> areaWalls = {-1, -1, -1, -1};
    double gain = 0.5;          ///< α in (0, 1]
    double maxSpeed = 0.0;      ///< v_max > 0, length/time

    bool active() const { return targetStress > 0.0; }
    bool areaFromWalls() const { return areaWalls[0] >= 0; }
};

/// The current area of servo wall @a b of @a world (its fixed area, or from its area walls).
double servoArea(const World& world, const Boundary& b);

/// The normal stress the grains put on plane wall @a b over @a area (compression positive).
double normalStress(const Boundary& b, double area);

/// The servo velocity of wall @a b (world vector along its normal) for a step of @a dt.
Vec3 servoVelocity(const World& world, const Boundary& b, double dt);

/// Set the velocity of every servo wall of @a world from the state at the start of a step.
void updateServoVelocities(World& world, double dt);

} // namespace lsdem
