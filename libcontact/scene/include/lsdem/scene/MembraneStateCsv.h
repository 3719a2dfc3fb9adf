/// @file MembraneStateCsv.h
/// @brief A membrane's vertices as a run left them, as CSV (x, y, z, vx, vy, vz, one row a
///        vertex in the membrane's own order): a scene's [[membranes]] `state` places a tube
///        where a run stretched and dented it, its rubber's unstretched shape still the tube's
///        keys' (docs/scenes.md).
#pragma once

#include "lsdem/simulation/Membrane.h"

#include <string>

namespace lsdem {

/// The CSV text of @a m's positions and velocities (17 significant digits: read back exactly).
std::string membraneStateCsvText(const Membrane& m);

/// Write membraneStateCsvText(@a m) to @a path atomically. @throw Error if it cannot be written.
void writeMembraneStateCsv(const Membrane& m, const std::string& path);

/// Set @a m's positions and velocities from the CSV file @a path. @throw Error naming the file
/// and line if it cannot be read, lacks a column, holds a value that is not a finite number, or
/// has other than one row per vertex of @a m.
void readMembraneStateCsv(const std::string& path, Membrane& m);

} // namespace lsdem
