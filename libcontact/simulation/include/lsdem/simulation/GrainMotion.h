/// @file GrainMotion.h
/// @brief How a grain moves: by the forces on it, not at all, or as prescribed; and the names
///        scenes, grain tables and Python give the three (one list for all of them).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

enum class GrainMotion {
    Free,        ///< moved by forces
    Fixed,       ///< never moves; feels and records forces
    Prescribed,  ///< moves at its given velocity and angular velocity, whatever the forces
};

/// "free", "fixed" or "prescribed".
inline std::string grainMotionName(GrainMotion motion)
{
    switch (motion) {
    case GrainMotion::Free: return "free";
    case GrainMotion::Fixed: return "fixed";
    case GrainMotion::Prescribed: return "prescribed";
    }
    return "free";
}

/// Every motion's name, in the enum's order.
inline std::vector<std::string> grainMotionNames()
{
    return {grainMotionName(GrainMotion::Free), grainMotionName(GrainMotion::Fixed),
            grainMotionName(GrainMotion::Prescribed)};
}

/// The motion named @a name, if there is one.
inline std::optional<GrainMotion> parseGrainMotion(const std::string& name)
{
    for (GrainMotion m : {GrainMotion::Free, GrainMotion::Fixed, GrainMotion::Prescribed})
        if (grainMotionName(m) == name) return m;
    return std::nullopt;
}

} // namespace lsdem
