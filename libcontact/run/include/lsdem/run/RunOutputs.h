/// @file RunOutputs.h
/// @brief The text outputs of a run, each written whole and atomically: `energy.csv` (global
///        energies per history step), `boundary_<name>.csv` (displacement and reaction force of
///        each boundary; for a servo wall also the current point of its plane, its area, stress,
///        target stress and speed along its normal), `membrane_<name>.csv` (each membrane's
///        pressure, enclosed volume, energies and the grains' push on it), `grains.csv` (every
///        grain's final state and displacement), in a periodic cell `cell.csv` (its size,
///        strain rates and stress) and, when asked, `micromechanics.csv`.
///        Numbers are printed with 17 significant digits so they read back exactly.
#pragma once

#include "lsdem/run/RunRecord.h"
#include "lsdem/simulation/Simulation.h"

#include <string>
#include <vector>

namespace lsdem {

/// The names of the text outputs in a run's folder.
inline const std::string kEnergyFileName = "energy.csv";
inline const std::string kGrainsFileName = "grains.csv";
inline const std::string kMicromechanicsFileName = "micromechanics.csv";
inline const std::string kCellFileName = "cell.csv";

/// Append the rows of the current state to @a record (one energy row, one row per boundary,
/// one row per membrane: step, time, pressure, enclosed volume, strain energy, kinetic energy,
/// the sum of the grains' push on its vertices (x, y, z) and the sum of that push's magnitudes,
/// in a periodic cell one row of its size, strain rates and stress along x, y, z (the stress
/// is measured only while the cell deforms: zero in a fixed cell), and with
/// record.micromechanics one row of Micromechanics.h's measures: the stress moment's nine
/// entries row by row, the fabric's six, its anisotropy, the contact and grain counts and the
/// mechanical coordination number).
/// Collective when the simulation is split by space (its energies and micromechanics are sums
/// over every rank, in one process's order: the same rows on every rank).
void recordHistoryRow(const Simulation& sim, RunRecord& record);

/// The micromechanics row of the current state (step, time, then as above). Collective when
/// split by space: computed on rank 0 from the whole simulation, the same on every rank.
std::vector<double> micromechanicsRow(const Simulation& sim);

/// Write energy.csv, boundary_<name>.csv, membrane_<name>.csv, (in a periodic cell) cell.csv
/// and (with record.micromechanics) micromechanics.csv in @a directory from @a record.
void writeHistoryFiles(const std::string& directory, const World& world,
                       const RunRecord& record);

/// Write grains.csv: name, position, orientation (w x y z), velocity, angular velocity and
/// the distance moved from @a initialPositions.
void writeGrainsFile(const std::string& path, const World& world,
                     const std::vector<Vec3>& initialPositions);

/// The file name used for boundary @a name ("boundary_<name>.csv", unsafe characters as '_').
std::string boundaryHistoryFileName(const std::string& name);

/// Whether @a fileName is the history of some boundary (as boundaryHistoryFileName names it).
bool isBoundaryHistoryFileName(const std::string& fileName);

/// The file name used for membrane @a name ("membrane_<name>.csv", unsafe characters as '_').
std::string membraneHistoryFileName(const std::string& name);

/// Whether @a fileName is the history of some membrane (as membraneHistoryFileName names it).
bool isMembraneHistoryFileName(const std::string& fileName);

/// Whether the file at @a path is a text output of a run (energy.csv, grains.csv, a boundary's
/// or a membrane's history): its first line is a header lsdem writes. A file of such a name
/// holding anything else is somebody else's.
bool isRunTextOutput(const std::string& path);

} // namespace lsdem
