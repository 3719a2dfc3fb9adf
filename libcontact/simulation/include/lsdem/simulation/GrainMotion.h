/// @file GrainMotion.h
/// @brief How a grain moves: by the forces on it, not at all, or as prescribed.
#pragma once

namespace lsdem {

enum class GrainMotion {
    Free,        ///< moved by forces
    Fixed,       ///< never moves; feels and records forces
    Prescribed,  ///< moves at its given velocity and angular velocity, whatever the forces
};

} // namespace lsdem
