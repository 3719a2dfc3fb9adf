#include "run/RunRanks.h"

#include "common/MpiLauncher.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace lsdem {

using cli::environmentCount;
using cli::launchedByMpi;

#ifdef LSDEM_WITH_MPI
// MpiRankGroup.cpp: the only file of lsdem-run that includes mpi.h.
std::unique_ptr<RunRanks> startMpiRunRanks(int& argc, char**& argv);
#endif

std::unique_ptr<RunRanks> startRunRanks(int& argc, char**& argv)
{
    const long long slurmTasks = environmentCount("SLURM_STEP_NUM_TASKS");
    if (!launchedByMpi() && slurmTasks > 1)
        throw Error("", "started as one of " + std::to_string(slurmTasks) +
                            " copies by srun without an MPI job: each copy would run the whole "
                            "simulation and write the same files",
                    "use srun --mpi=pmix (or mpirun inside the allocation)");
#ifdef LSDEM_WITH_MPI
    if (launchedByMpi()) return startMpiRunRanks(argc, argv);
#else
    (void)argc;
    (void)argv;
    const long long launched =
        std::max(environmentCount("OMPI_COMM_WORLD_SIZE"), environmentCount("PMI_SIZE"));
    if (launchedByMpi() && launched > 1)
        throw Error("", "started as " + std::to_string(launched) +
                            " copies by an MPI launcher, but this lsdem-run was built without "
                            "MPI: each copy would run the whole simulation and write the same "
                            "files",
                    "rebuild with MPI (libopenmpi-dev; cmake -DLSDEM_MPI=ON), or run one copy "
                    "without mpirun");
#endif
    return nullptr;
}

} // namespace lsdem
