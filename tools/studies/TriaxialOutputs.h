/// @file TriaxialOutputs.h
/// @brief The files of the triaxial study: every recorded row of every run, and one summary row
///        per run. Both written atomically.
#pragma once

#include "studies/TriaxialStudy.h"

#include <cmath>
#include <string>
#include <vector>

namespace lsdem {

/// DIR/triaxial.csv: formulation, sdp, seed, nodes, stage, step, time, strains, stresses, p, q, q/p,
/// mobilised friction angle, void ratio, coordination, inertial number, kinetic energy, size.
void writeTriaxialCsv(const TriaxialStudyResult& r, const std::string& path);

/// DIR/triaxial_runs.csv: one row per run: resolution, seed, stiffness, time step, steps, the
/// consolidated state, peak and critical-state figures, cost.
void writeTriaxialRunsCsv(const TriaxialStudyResult& r, const std::string& path);

/// A formulation and SDP's figures over the study's seeds (one run each): the mean and the
/// sample standard deviation (NaN for one seed).
struct TriaxialSeedMean
{
    Formulation formulation = Formulation::Adapted;
    double sdp = 0.0;
    int seeds = 0;
    double peakFrictionAngle = 0.0, peakFrictionAngleSpread = std::nan("");  ///< degrees
    double secantModulus50 = 0.0, secantModulus50Spread = std::nan("");      ///< MPa
};

/// One entry per formulation and SDP, in the order of the study's runs.
std::vector<TriaxialSeedMean> triaxialSeedMeans(const TriaxialStudyResult& r);

/// Successive SDPs of one formulation compared seed by seed (issue 36: the seeds' samples are
/// the same at both, so their differences are paired): the finer run's figure minus the
/// coarser's, per seed, and the mean, sample standard deviation and standard error (sd/√n) of
/// those differences (NaN spreads for one seed); and the mean nodes per grain–grain contact of
/// the consolidated samples at each SDP, the resolution the contact law had.
struct TriaxialPairedChange
{
    Formulation formulation = Formulation::Adapted;
    double coarseSdp = 0.0, fineSdp = 0.0;
    int seeds = 0;  ///< seeds run at both
    double coarseNodesPerContact = 0.0, fineNodesPerContact = 0.0;
    double peakFrictionAngle = 0.0, peakFrictionAngleSpread = std::nan(""),
           peakFrictionAngleError = std::nan("");  ///< φ_fine − φ_coarse, degrees
    double secantModulus50 = 0.0, secantModulus50Spread = std::nan(""),
           secantModulus50Error = std::nan("");  ///< E_fine/E_coarse − 1
};

/// One entry per formulation and pair of successive SDPs (coarsest first) with a seed run at
/// both, in the order of the study's runs.
std::vector<TriaxialPairedChange> triaxialPairedChanges(const TriaxialStudyResult& r);

/// DIR/triaxial_convergence.csv: the entries of triaxialPairedChanges, one row each.
void writeTriaxialConvergenceCsv(const TriaxialStudyResult& r, const std::string& path);

/// The change of the peak friction angle between the two finest SDPs of @a f (degrees; of the
/// means over the seeds), NaN if the study ran @a f at fewer than two SDPs.
double finestPeakChange(const TriaxialStudyResult& r, Formulation f);

/// The relative change of E₅₀ (of the means over the seeds) between the two finest SDPs of @a f
/// (0.1: 10 % stiffer at the finest), NaN if there are fewer than two.
double finestModulusChange(const TriaxialStudyResult& r, Formulation f);

} // namespace lsdem
