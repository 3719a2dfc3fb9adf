#include "studies/RunDistributor.h"

#include "common/MpiLauncher.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace lsdem {

using cli::environmentCount;
using cli::launchedByMpi;

#ifdef LSDEM_WITH_MPI
// MpiRunDistributor.cpp: the only file that includes mpi.h.
std::unique_ptr<RunDistributor> makeMpiRunDistributor(int& argc, char**& argv,
                                                      const std::string& toolName);
#endif

namespace {

class SerialRunDistributor final : public RunDistributor
{
public:
    int rank() const override { return 0; }
    int ranks() const override { return 1; }
    int threadsPerRank() const override { return 0; }
    void runAll(const std::vector<std::string>& descriptions, const std::vector<double>&,
                const Job& job, const ResultSink& onResult) override
    {
        for (size_t i = 0; i < descriptions.size(); ++i) onResult(i, 0, job(descriptions[i]));
    }
    void serve(const Job&) override
    {
        throw std::logic_error("serial run distributor: only rank 0 exists, nothing to serve");
    }
    void finish() override {}
};

} // namespace

bool builtWithMpi()
{
#ifdef LSDEM_WITH_MPI
    return true;
#else
    return false;
#endif
}

RunDistributor& serialRunDistributor()
{
    static SerialRunDistributor serial;
    return serial;
}

std::unique_ptr<RunDistributor> makeRunDistributor(int& argc, char**& argv,
                                                   const std::string& toolName)
{
    const long long launched = std::max(environmentCount("OMPI_COMM_WORLD_SIZE"),
                                        environmentCount("PMI_SIZE"));
#ifdef LSDEM_WITH_MPI
    if (launchedByMpi()) return makeMpiRunDistributor(argc, argv, toolName);
#else
    (void)argc;
    (void)argv;
    (void)toolName;
    // Every copy would run the whole study and write the same files.
    if (launched > 1)
        throw Error("", "started by an MPI launcher with " + std::to_string(launched) +
                            " ranks, but this " + toolName + " was built without MPI",
                    "run it without mpirun, or install libopenmpi-dev and rebuild (CMake finds "
                    "MPI by itself; -DLSDEM_MPI=ON insists)");
#endif
    // srun without an MPI plugin starts independent copies that would each run everything.
    const long long tasks = environmentCount("SLURM_STEP_NUM_TASKS");
    if (tasks > 1 && launched <= 1 && !launchedByMpi())
        throw Error("", "srun started " + std::to_string(tasks) +
                            " tasks that do not form one MPI job",
                    "give srun the MPI plugin Open MPI uses, e.g. srun --mpi=pmix, or use mpirun "
                    "inside the allocation");
    return std::unique_ptr<RunDistributor>(new SerialRunDistributor);
}

} // namespace lsdem
