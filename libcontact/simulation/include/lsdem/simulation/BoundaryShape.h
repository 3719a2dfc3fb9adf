/// @file BoundaryShape.h
/// @brief The kinds of rigid boundary a simulation offers.
#pragma once

namespace lsdem {

enum class BoundaryShape {
    Plane,     ///< half-space wall; grains live on the side its normal points to
    Sphere,    ///< rigid sphere (an indenter); grains live outside it
    LevelSet,  ///< a baked asset used as a rigid obstacle; grains live outside it
    Cylinder,  ///< the side wall of an infinitely long circular cylinder; grains live inside it
    Orifice,   ///< a flat plate with a circular hole (a silo's floor); grains live outside it
};

} // namespace lsdem
