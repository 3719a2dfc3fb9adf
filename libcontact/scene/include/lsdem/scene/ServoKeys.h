/// @file ServoKeys.h
/// @brief The rules of a servo wall's keys (docs/scenes.md, [[boundaries]]), written once for
///        every front end: the scene reader gathers what a [[boundaries]] entry gives, Python's
///        add_plane what its arguments give, and both ask applyServoKeys, which names the key
///        at fault in the same words.
#pragma once

#include "lsdem/scene/EntryRules.h"
#include "lsdem/scene/Scene.h"

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

/// What a plane's entry gives of the servo's keys (nothing given: std::nullopt).
struct ServoKeys
{
    std::optional<double> stress;                       ///< target normal stress, > 0
    std::optional<double> area;                         ///< the area it acts on, > 0 ...
    std::optional<std::vector<std::string>> areaWalls;  ///< ... or between four walls
    std::optional<double> maxSpeed;                     ///< limit speed, > 0
    std::optional<double> gain;                         ///< servo_gain, in (0, 1]
    bool velocityGiven = false;                         ///< the entry moves the wall itself
};

/// The first rule @a keys break, checked in the order a reader meets them; if none, the servo
/// is set on @a wall (its servo and areaWallNames) and nothing is returned. Without a stress the
/// other keys are refused and the wall is left as it was.
std::optional<KeyProblem> applyServoKeys(const ServoKeys& keys, BoundarySpec& wall);

} // namespace lsdem
