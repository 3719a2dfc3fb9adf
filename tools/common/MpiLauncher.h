/// @file MpiLauncher.h
/// @brief How a program learns, before touching MPI, whether an MPI launcher started it: the
///        launchers set their rank or size in the environment. Shared by lsdem-study's run
///        distributor and lsdem-run's ranks.
#pragma once

#include <cstdlib>

namespace lsdem::cli {

/// A count from the environment variable @a name, or 0.
inline long long environmentCount(const char* name)
{
    const char* text = std::getenv(name);
    return text ? std::atoll(text) : 0;
}

/// Whether an MPI launcher started this process: each sets its rank or size in the
/// environment (Open MPI's mpirun, MPICH's hydra, PMI-1/2 and PMIx, which srun uses).
inline bool launchedByMpi()
{
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK",
                             "MPI_LOCALNRANKS"})
        if (std::getenv(name)) return true;
    return false;
}

} // namespace lsdem::cli
