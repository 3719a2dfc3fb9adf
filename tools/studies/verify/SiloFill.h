/// @file SiloFill.h
/// @brief What the silo case measures of its settled fill before the orifice opens: the height
///        of its free surface and the bulk density of its core, for Beverloo's law.
#pragma once

#include "studies/verify/SiloPlan.h"

#include "lsdem/simulation/World.h"

namespace lsdem::verify {

/// The height of the fill's free surface: the median, over square columns 2·@a size wide, of
/// each column's highest grain centre. A median, so that one grain lying high (or a heap in
/// one place) does not raise it: the highest centre over the whole fill would.
double fillSurface(const World& w, double size);

/// The bulk density of the settled fill: the mass of the grains whose centres lie in its core
/// (two grain sizes @a size from the silo's wall, the floor and the free surface) over the
/// core's volume.
double bulkDensity(const World& w, const SiloPlan& p, double size);

} // namespace lsdem::verify
