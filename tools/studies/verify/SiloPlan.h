/// @file SiloPlan.h
/// @brief The silo case's plan (its geometry, grains, law and what it measures) as the quick
///        or full version and the options make it; shared by the case and its cost estimate.
#pragma once

#include <string>
#include <vector>

namespace lsdem::verify {

/// The silo, its grains' law and what is measured; lengths in grain sizes d ≈ 1 mm.
struct SiloPlan
{
    /// mm: Beverloo's premise wants the silo at least 2.5 orifices and D + 30 d wide (the
    /// default's 20 d is not the second: see addBeverlooChecks)
    double siloRadius = 10.0;
    double fillHeight = 12.0;      ///< mm above the floor
    double plateThickness = 0.5;   ///< mm: ≫ any overlap
    std::vector<double> orifices;  ///< D, mm
    long long grains = 0;
    /// The flow is measured from the countFrom-th grain out to the countTo-th: past the start's
    /// transient, and while the silo is still more than ~3/4 full.
    int countFrom = 200, countTo = 900;
    double settleTime = 0.05;      ///< s under the real law before the orifice opens
    double clogTime = 0.1;         ///< s without a grain out: the orifice has clogged
    double framePeriod = 0.02;     ///< s between frames (of the largest orifice)
    int frames = 20;
    // The law: soft enough that a step resolves collisions at a few m/s with overlaps of ~1 %
    // of d, stiff enough that the weight of the column presses contacts by ~1 % of d.
    double knStar = 10.0;          ///< N/mm³
    double ksStar = 5.0;           ///< N/mm³
    double friction = 0.5;
    double restitution = 0.5;
    double density = 2.65e-9;      ///< t/mm³ (quartz)
    double gravity = 9810.0;       ///< mm/s²
};

/// The plan of the quick or full version with the silo's radius, fill height and orifices as
/// asked (0 or none: the plan's own).
SiloPlan planAsAsked(bool quick, double siloRadius, double siloHeight,
                     const std::vector<double>& orifices);

/// Whether @a kinds ("spheres", "sand") holds @a kind.
bool wantsKind(const std::vector<std::string>& kinds, const char* kind);

} // namespace lsdem::verify
