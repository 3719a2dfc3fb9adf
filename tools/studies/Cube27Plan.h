/// @file Cube27Plan.h
/// @brief The loading plan of the 3×3×3 stack study, all from closed forms at δ_max so its
///        cost is known before any run starts: per run, the contact stiffnesses of a column,
///        the time step from the stiffest grain, the loading time from the slowest column mode,
///        the wall speed and the steps (see Cube27Study.h).
#pragma once

#include "studies/Cube27Options.h"

#include "lsdem/contact/NormalModel.h"

#include <vector>

namespace lsdem {

/// One simulation of the study: a formulation, node count, stiffness and orientation set.
struct Cube27Run
{
    Formulation formulation = Formulation::Adapted;
    int nodes = 0;
    double stiffness = 0.0;
    int orientation = 0;
    // The loading plan.
    double timeStep = 0.0;    ///< s
    long long steps = 0;      ///< loading steps
    double speed = 0.0;       ///< mm/s
    double stabilityLimit = 0.0;  ///< the planned stiffest grain's limit 2/ω_max, s
    // What happened.
    double seconds = 0.0;
    double stabilityLimitSeen = 0.0;  ///< Simulation's smallest limit met, s
    long long contactNodes = 0;       ///< penetrating nodes at the end
};

/// Plan the loading of one run (time step, steps, speed) from closed forms; see the file note.
Cube27Run planCube27Run(const Cube27Options& o, Formulation f, int nodes, double stiffness,
                        int orientation);

/// All runs of the study, in the order they are made (per node count: formulations ×
/// stiffnesses × orientations).
std::vector<Cube27Run> planCube27(const Cube27Options& o);

} // namespace lsdem
