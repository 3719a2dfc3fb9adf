#include "lsdem/simulation/StressServo.h"

#include "lsdem/simulation/World.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lsdem {

namespace {

/// The distance between the current planes of walls @a a and @a b (measured along a's normal).
double wallGap(const World& world, int a, int b)
{
    const Boundary& wa = world.boundaries[static_cast<size_t>(a)];
    const Boundary& wb = world.boundaries[static_cast<size_t>(b)];
    return std::abs((wb.referencePoint() - wa.referencePoint()).dot(wa.plane.normal));
}

} // namespace

double servoArea(const World& world, const Boundary& b)
{
    const StressServo& s = b.servo;
    if (!s.areaFromWalls()) return s.area;
    return wallGap(world, s.areaWalls[0], s.areaWalls[1]) *
           wallGap(world, s.areaWalls[2], s.areaWalls[3]);
}

double normalStress(const Boundary& b, double area)
{
    // The grains push the wall against its normal (which points towards them).
    const double stress = area > 0.0 ? -b.force.dot(b.plane.normal) / area : 0.0;
    return stress == 0.0 ? 0.0 : stress;  // +0 without contact (a CSV shows "-0" otherwise)
}

Vec3 servoVelocity(const World& world, const Boundary& b, double dt)
{
    const StressServo& s = b.servo;
    const double area = servoArea(world, b);
    const double error = s.targetStress - normalStress(b, area);  // > 0: push further in
    double speed = 0.0;
    // Moving at v for a step changes the force by K·v·Δt (springs) + C·v (dashpots).
    const double response = b.normalStiffness * dt + b.normalDashpot;
    if (response > 0.0)
        speed = s.gain * error * area / response;
    else
        speed = error > 0.0 ? s.maxSpeed : error < 0.0 ? -s.maxSpeed : 0.0;
    speed = std::clamp(speed, -s.maxSpeed, s.maxSpeed);
    return speed * b.plane.normal;
}

void updateServoVelocities(World& world, double dt)
{
    // All from the state before any wall moves, so the order of the walls does not matter.
    std::vector<Vec3> velocities(world.boundaries.size());
    for (size_t i = 0; i < world.boundaries.size(); ++i)
        if (world.boundaries[i].servo.active())
            velocities[i] = servoVelocity(world, world.boundaries[i], dt);
    for (size_t i = 0; i < world.boundaries.size(); ++i)
        if (world.boundaries[i].servo.active()) world.boundaries[i].velocity = velocities[i];
}

} // namespace lsdem
