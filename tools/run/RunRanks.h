/// @file RunRanks.h
/// @brief The MPI job lsdem-run may be one rank of (`mpirun -n N lsdem-run ...`): the ranks its
///        simulation's contacts are split over (lsdem/simulation/RankGroup.h), how many share
///        this machine, and how a failure on one rank ends the job rather than leaving the
///        other ranks waiting. MPI itself is in MpiRankGroup.cpp, built only with MPI.
#pragma once

#include "lsdem/simulation/RankGroup.h"

#include <functional>
#include <memory>
#include <string>

namespace lsdem {

class RunRanks
{
public:
    virtual ~RunRanks() = default;

    virtual RankGroup& group() = 0;
    /// Ranks of this job on this machine (for the threads each should use).
    virtual int ranksOnThisMachine() const = 0;

    /// Run @a body on this rank and return its exit code. If it throws (lsdem::Error: exit
    /// code 1; anything else: 3) on every rank, as a bad scene or an unstable time step does,
    /// rank 0 prints the message once and every rank returns the code; if it throws on some
    /// ranks only, a failing rank prints its message (naming its rank) and ends the whole job.
    virtual int run(const std::string& toolName, const std::function<int()>& body) = 0;
};

/// The job this process is a rank of: MPI's (initialised here, finalised by the destructor)
/// when lsdem was built with MPI and an MPI launcher started the program; otherwise null
/// (one process, MPI untouched).
/// @throw Error if an MPI launcher started several copies of a build without MPI (each would
///        run the whole simulation and write the same files).
std::unique_ptr<RunRanks> startRunRanks(int& argc, char**& argv);

} // namespace lsdem
