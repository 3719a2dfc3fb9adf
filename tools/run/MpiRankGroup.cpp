// lsdem-run's ranks over MPI (RunRanks.h): the all-gather, the all-to-all of ghosts and
// the stop vote on one communicator, the agreement on a failure on another (so a failing
// rank's vote can never be mistaken for a step's exchange). The only file of lsdem-run that
// includes mpi.h; MPI is called from the main thread only (MPI_THREAD_FUNNELED).
#include "run/RunRanks.h"

#include "lsdem/core/Error.h"

#include <mpi.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <thread>

namespace lsdem {

namespace {

/// How long ranks that failed wait for the others to fail too before ending the job: a
/// failure of the shared state (bad scene, unstable step) reaches every rank at the same
/// step, within moments of each other.
constexpr auto kFailureAgreement = std::chrono::seconds(3);

class MpiRankGroup final : public RankGroup
{
public:
    explicit MpiRankGroup(MPI_Comm comm) : mComm(comm)
    {
        MPI_Comm_rank(mComm, &mRank);
        MPI_Comm_size(mComm, &mRanks);
    }

    int rank() const override { return mRank; }
    int ranks() const override { return mRanks; }

    void allGather(const std::vector<char>& mine, std::vector<char>& all,
                   std::vector<size_t>& starts) override
    {
        if (mine.size() > size_t(INT_MAX))
            throw std::length_error("a rank's slot results exceed one MPI message (2 GiB)");
        const int size = static_cast<int>(mine.size());
        mCounts.resize(size_t(mRanks));
        MPI_Allgather(&size, 1, MPI_INT, mCounts.data(), 1, MPI_INT, mComm);
        mDisplacements.resize(size_t(mRanks));
        starts.assign(size_t(mRanks) + 1, 0);
        for (int r = 0; r < mRanks; ++r) {
            starts[size_t(r) + 1] = starts[size_t(r)] + size_t(mCounts[size_t(r)]);
            if (starts[size_t(r)] > size_t(INT_MAX))
                throw std::length_error("the slot results of all ranks exceed 2 GiB");
            mDisplacements[size_t(r)] = static_cast<int>(starts[size_t(r)]);
        }
        all.resize(starts.back());
        MPI_Allgatherv(mine.data(), size, MPI_BYTE, all.data(), mCounts.data(),
                       mDisplacements.data(), MPI_BYTE, mComm);
    }

    void allToAll(const std::vector<std::vector<char>>& toEach, std::vector<char>& received,
                  std::vector<size_t>& starts) override
    {
        mSendCounts.resize(size_t(mRanks));
        mSendDisplacements.resize(size_t(mRanks));
        mCounts.resize(size_t(mRanks));
        mDisplacements.resize(size_t(mRanks));
        mSendBytes.clear();
        for (int r = 0; r < mRanks; ++r) {
            const std::vector<char>& bytes = toEach[size_t(r)];
            if (mSendBytes.size() + bytes.size() > size_t(INT_MAX))
                throw std::length_error("a rank's ghosts exceed one MPI message (2 GiB)");
            mSendDisplacements[size_t(r)] = static_cast<int>(mSendBytes.size());
            mSendCounts[size_t(r)] = static_cast<int>(bytes.size());
            mSendBytes.insert(mSendBytes.end(), bytes.begin(), bytes.end());
        }
        MPI_Alltoall(mSendCounts.data(), 1, MPI_INT, mCounts.data(), 1, MPI_INT, mComm);
        starts.assign(size_t(mRanks) + 1, 0);
        for (int r = 0; r < mRanks; ++r) {
            starts[size_t(r) + 1] = starts[size_t(r)] + size_t(mCounts[size_t(r)]);
            if (starts[size_t(r) + 1] > size_t(INT_MAX))
                throw std::length_error("the ghosts and grains a rank receives exceed 2 GiB");
            mDisplacements[size_t(r)] = static_cast<int>(starts[size_t(r)]);
        }
        received.resize(starts.back());
        MPI_Alltoallv(mSendBytes.data(), mSendCounts.data(), mSendDisplacements.data(), MPI_BYTE,
                      received.data(), mCounts.data(), mDisplacements.data(), MPI_BYTE, mComm);
    }

    bool anyRank(bool mine) override
    {
        int in = mine ? 1 : 0, out = 0;
        MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, mComm);
        return out != 0;
    }

private:
    MPI_Comm mComm;
    int mRank = 0, mRanks = 1;
    std::vector<int> mCounts, mDisplacements, mSendCounts, mSendDisplacements;
    std::vector<char> mSendBytes;
};

class MpiRunRanks final : public RunRanks
{
public:
    MpiRunRanks(int& argc, char**& argv)
    {
        int provided = 0;
        MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
        MPI_Comm_dup(MPI_COMM_WORLD, &mWork);
        MPI_Comm_dup(MPI_COMM_WORLD, &mFailures);
        mGroup = std::make_unique<MpiRankGroup>(mWork);
        MPI_Comm machine;
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
        MPI_Comm_size(machine, &mRanksHere);
        MPI_Comm_free(&machine);
    }

    ~MpiRunRanks() override
    {
        mGroup.reset();
        MPI_Comm_free(&mFailures);
        MPI_Comm_free(&mWork);
        MPI_Finalize();
    }

    RankGroup& group() override { return *mGroup; }
    int ranksOnThisMachine() const override { return mRanksHere; }

    int run(const std::string& toolName, const std::function<int()>& body) override
    {
        try {
            return body();
        } catch (const Error& e) {
            return failed(toolName, 1, std::string("error: ") + e.what());
        } catch (const std::exception& e) {
            return failed(toolName, 3, std::string("internal error: ") + e.what());
        }
    }

private:
    /// This rank failed with @a message: if every rank fails within kFailureAgreement (the
    /// shared state went wrong everywhere), rank 0 prints the message and all return
    /// @a exitCode; otherwise this rank prints it and ends the job.
    int failed(const std::string& toolName, int exitCode, const std::string& message)
    {
        MPI_Request everyone;
        MPI_Ibarrier(mFailures, &everyone);
        const auto until = std::chrono::steady_clock::now() + kFailureAgreement;
        int done = 0;
        while (!done && std::chrono::steady_clock::now() < until) {
            MPI_Test(&everyone, &done, MPI_STATUS_IGNORE);
            if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        const int rank = mGroup->rank();
        std::fflush(stdout);
        if (done) {
            if (rank == 0) std::fprintf(stderr, "%s: %s\n", toolName.c_str(), message.c_str());
            std::fflush(stderr);
            return exitCode;
        }
        std::fprintf(stderr, "%s (rank %d of %d): %s\n", toolName.c_str(), rank,
                     mGroup->ranks(), message.c_str());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, exitCode);
        std::abort();  // MPI_Abort does not return; this tells the compiler so
    }

    MPI_Comm mWork = MPI_COMM_NULL, mFailures = MPI_COMM_NULL;
    std::unique_ptr<MpiRankGroup> mGroup;
    int mRanksHere = 1;
};

} // namespace

std::unique_ptr<RunRanks> startMpiRunRanks(int& argc, char**& argv)
{
    return std::make_unique<MpiRunRanks>(argc, argv);
}

} // namespace lsdem
