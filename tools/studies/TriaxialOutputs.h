/// @file TriaxialOutputs.h
/// @brief The files of the triaxial study: every recorded row of every run, and one summary row
///        per run. Both written atomically.
#pragma once

#include "studies/TriaxialStudy.h"

#include <string>

namespace lsdem {

/// DIR/triaxial.csv: formulation, sdp, nodes, stage, step, time, strains, stresses, p, q, q/p,
/// mobilised friction angle, void ratio, coordination, inertial number, kinetic energy, size.
void writeTriaxialCsv(const TriaxialStudyResult& r, const std::string& path);

/// DIR/triaxial_runs.csv: one row per run: resolution, stiffness, time step, steps, the
/// consolidated state, peak and critical-state figures, cost.
void writeTriaxialRunsCsv(const TriaxialStudyResult& r, const std::string& path);

/// The change of the peak friction angle between the two finest SDPs of @a f (degrees), NaN if
/// the study ran @a f at fewer than two SDPs.
double finestPeakChange(const TriaxialStudyResult& r, Formulation f);

/// The relative change of E₅₀ between the two finest SDPs of @a f (0.1: 10 % stiffer at the
/// finest), NaN if there are fewer than two.
double finestModulusChange(const TriaxialStudyResult& r, Formulation f);

} // namespace lsdem
