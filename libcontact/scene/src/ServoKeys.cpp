#include "lsdem/scene/ServoKeys.h"

#include "lsdem/core/NumberRange.h"

namespace lsdem {

std::optional<KeyProblem> applyServoKeys(const ServoKeys& k, BoundarySpec& wall)
{
    if (!k.stress) {
        for (const auto& [key, given] : {std::pair{"area", k.area.has_value()},
                                         {"area_walls", k.areaWalls.has_value()},
                                         {"max_speed", k.maxSpeed.has_value()},
                                         {"servo_gain", k.gain.has_value()}})
            if (given)
                return KeyProblem{key, "only makes sense for a servo wall",
                                    "give stress (the target normal stress) or remove " +
                                        std::string(key)};
        return std::nullopt;
    }
    StressServo servo;
    if (std::optional<std::string> p = outOfRange(NumberRange::Positive, *k.stress))
        return KeyProblem{"stress", *p + ": a wall can only push on the grains, so its stress is "
                                           "compressive",
                            "give the compressive stress as a positive number (force/length²)"};
    servo.targetStress = *k.stress;
    if (k.velocityGiven)
        return KeyProblem{"velocity", "a servo wall chooses its own velocity",
                            "remove velocity, or remove stress for a wall moving at a fixed "
                            "velocity"};
    if (k.area && k.areaWalls)
        return KeyProblem{"area_walls", "both area and area_walls are given", "keep one of them"};
    if (!k.area && !k.areaWalls)
        return KeyProblem{"stress", "a servo wall needs the area its stress acts on",
                            "give area (length²) or area_walls, the names of two pairs of "
                            "opposite walls around it, e.g. [\"left\", \"right\", \"front\", "
                            "\"back\"]"};
    if (k.area) {
        if (std::optional<std::string> p = outOfRange(NumberRange::Positive, *k.area))
            return KeyProblem{"area", *p, "give the area the stress acts on (length²)"};
        servo.area = *k.area;
    } else if (k.areaWalls->size() != 4) {
        return KeyProblem{"area_walls", "expected the names of four walls (two opposite pairs)",
                            "give e.g. [\"left\", \"right\", \"front\", \"back\"]"};
    }
    if (!k.maxSpeed)
        return KeyProblem{"stress", "a servo wall needs a limit speed",
                            "give max_speed (length/time): how fast it may move towards its "
                            "stress"};
    if (std::optional<std::string> p = outOfRange(NumberRange::Positive, *k.maxSpeed))
        return KeyProblem{"max_speed", *p, "how fast it may move towards its stress"};
    servo.maxSpeed = *k.maxSpeed;
    if (k.gain) {
        if (std::optional<std::string> p = outOfRange(NumberRange::PositiveFraction, *k.gain))
            return KeyProblem{"servo_gain", *p,
                                "0.5 is the default; a gain above 1 overshoots the target "
                                "every step"};
        servo.gain = *k.gain;
    }
    wall.servo = servo;
    wall.areaWallNames = k.areaWalls ? *k.areaWalls : std::vector<std::string>{};
    return std::nullopt;
}

} // namespace lsdem
