/// @file Cube27Options.h
/// @brief What the 3×3×3 sphere-stack study runs (Feldfogel et al. 2024, Fig. 4), with the
///        checks made before anything runs. Units: mm, N, s, tonne.
#pragma once

#include "studies/SphereSeriesOptions.h"

namespace lsdem {

struct Cube27Options : SphereSeriesOptions
{
    Cube27Options()
    {
        nodeCounts = {500, 1000, 2000, 4000, 8000};
        kSeriesNodes = 4000;  // the paper's N for Fig. 4C, 4E
        voxel = 0.1;
        deltaMax = 0.3;       // top wall travel
        orientations = 1;
        outDir = "results/cube27";
    }
    double speed = 0.0;             ///< mm/s; 0: from `periods` (dynamically similar runs)
    long long steps = 0;            ///< loading steps; 0: from the time step below
    double periods = 100.0;         ///< loading time in periods of a column's slowest mode
    double safety = 0.2;            ///< dt as a fraction of the stiffest grain's stability limit
    int points = 30;                ///< δ values recorded (plus δ = 0)
    double density = 7.85e-9;       ///< tonne/mm³ (steel)
    double friction = 0.3;
    double shearRatio = 0.5;        ///< ks/kn (ks*/kn*)
    double restitution = 0.5;       ///< contact dashpots
    double globalDamping = 0.3;
};

/// The paper-like study (--full): nodes 500 … 16000, three orientations, voxel 0.05 mm.
Cube27Options cube27FullOptions();

/// Check @a o and throw Error naming the bad option and the fix.
void checkCube27Options(const Cube27Options& o);

} // namespace lsdem
