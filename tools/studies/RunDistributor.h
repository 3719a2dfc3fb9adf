/// @file RunDistributor.h
/// @brief Where a study's independent runs are done: one after the other in this process, or
///        spread over the ranks of an MPI job (`mpirun -n N lsdem-study ...`). The one place
///        that knows about MPI: a study describes each run as bytes (lsdem/core/ByteWriter.h), gets each
///        result back as bytes on rank 0, and writes its files there; the other ranks only do
///        the runs rank 0 hands them.
///
/// A study's code is the same on every rank:
/// @code
///   if (!ranks.isRoot()) { ranks.serve(job); return {}; }   // the other ranks: runs only
///   ranks.runAll(descriptions, costs, job, onResult);         // rank 0: may be called again
///   ranks.finish();                                           // release the other ranks
/// @endcode
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lsdem {

class RunDistributor
{
public:
    /// Does one run from its description and returns its result. Runs on whichever rank is
    /// free (rank 0 included, on a thread of its own): it must not write the study's files.
    using Job = std::function<std::string(const std::string& description)>;
    /// Sees a result on rank 0 as it arrives: the run's index in the batch, the rank that did
    /// it, the result. Called on rank 0's main thread, one at a time.
    using ResultSink = std::function<void(size_t index, int rank, const std::string& result)>;

    virtual ~RunDistributor() = default;

    virtual int rank() const = 0;
    virtual int ranks() const = 0;
    bool isRoot() const { return rank() == 0; }
    /// Worker threads each rank should use by default: the cores of its machine shared among
    /// the ranks on it (0: no advice, use all cores).
    virtual int threadsPerRank() const = 0;

    /// On rank 0: do the runs @a descriptions, each once, and give every result to @a onResult.
    /// Serial: in the given order, as they come. MPI: largest @a costs first (any unit), each
    /// to the first rank that is free, so the ranks finish together. A run that throws is an
    /// error of the whole study: serially it passes on; under MPI rank 0 prints it (naming the
    /// run and its rank) and ends the job with exit code 1 (lsdem::Error) or 3.
    virtual void runAll(const std::vector<std::string>& descriptions,
                        const std::vector<double>& costs, const Job& job,
                        const ResultSink& onResult) = 0;

    /// On the other ranks: do the runs rank 0 hands out with @a job until rank 0 calls finish.
    virtual void serve(const Job& job) = 0;

    /// On rank 0: tell the other ranks that there are no more runs (their serve returns).
    /// Safe to call twice; the destructor calls it.
    virtual void finish() = 0;
};

/// The distributor of this process: MPI's when lsdem was built with MPI and the program was
/// started by an MPI launcher (mpirun, mpiexec, srun; MPI is initialised here, with the
/// arguments, and finalised by the distributor's destructor); otherwise the serial one, and
/// MPI is not touched. @a toolName prefixes the messages of a failed run.
std::unique_ptr<RunDistributor> makeRunDistributor(int& argc, char**& argv,
                                                   const std::string& toolName);

/// A distributor that does every run here, in order (what lsdem-study does without MPI, and
/// what the study functions use when given none).
RunDistributor& serialRunDistributor();

/// Whether this build can spread runs over MPI ranks.
bool builtWithMpi();

} // namespace lsdem
