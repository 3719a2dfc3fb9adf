// The run distributor over MPI (RunDistributor.h): rank 0 hands the runs out largest first to
// whichever rank is free, does runs itself on a second thread meanwhile, and receives every
// result as bytes. The only file that includes mpi.h; MPI calls come from the main thread only
// (MPI_THREAD_FUNNELED).
#include "studies/RunDistributor.h"

#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"
#include "studies/RunSchedule.h"

#include "lsdem/core/Error.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

namespace lsdem {

namespace {

constexpr int kTagRun = 1;     ///< rank 0 to a worker: index, description
constexpr int kTagStop = 2;    ///< rank 0 to a worker: no more runs (empty)
constexpr int kTagResult = 3;  ///< a worker to rank 0: index, status, result or message

/// Waiting polls at this interval instead of blocking: Open MPI's blocking calls spin at full
/// speed, which would take a core from the ranks computing on the same machine.
constexpr auto kPollInterval = std::chrono::milliseconds(2);

enum class Status : long long
{
    Done = 0,
    BadInput = 1,  ///< the run threw lsdem::Error: the message is its text
    Failed = 2,    ///< any other exception
};

/// A finished run: where it came from and what it gave.
struct Outcome
{
    size_t index = 0;
    int rank = 0;
    Status status = Status::Done;
    std::string bytes;  ///< the result, or the error's message
};

Outcome runOne(const RunDistributor::Job& job, size_t index, const std::string& description,
               int rank)
{
    Outcome o{index, rank, Status::Done, {}};
    try {
        o.bytes = job(description);
    } catch (const Error& e) {
        o.status = Status::BadInput;
        o.bytes = e.what();
    } catch (const std::exception& e) {
        o.status = Status::Failed;
        o.bytes = e.what();
    }
    return o;
}

void send(const std::string& bytes, int destination, int tag)
{
    if (bytes.size() > size_t(INT_MAX))
        throw std::length_error("a run's result of " + std::to_string(bytes.size()) +
                                " bytes is too large for one MPI message");
    MPI_Send(bytes.data(), int(bytes.size()), MPI_BYTE, destination, tag, MPI_COMM_WORLD);
}

/// A message from @a source with @a tag (MPI_ANY_* allowed), if one is waiting.
std::optional<MPI_Status> waiting(int source, int tag)
{
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return std::nullopt;
    return status;
}

std::string receive(const MPI_Status& status)
{
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::string bytes(size_t(count), '\0');
    MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return bytes;
}

class MpiRunDistributor final : public RunDistributor
{
public:
    MpiRunDistributor(int& argc, char**& argv, const std::string& toolName) : mToolName(toolName)
    {
        int provided = 0;
        MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
        MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
        MPI_Comm_size(MPI_COMM_WORLD, &mRanks);
        MPI_Comm machine;
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
        MPI_Comm_size(machine, &mRanksHere);
        MPI_Comm_free(&machine);
    }

    ~MpiRunDistributor() override
    {
        if (isRoot()) finish();
        MPI_Finalize();
    }

    int rank() const override { return mRank; }
    int ranks() const override { return mRanks; }
    int threadsPerRank() const override
    {
        const int cores = int(std::thread::hardware_concurrency());
        return cores > 0 ? std::max(1, cores / std::max(1, mRanksHere)) : 0;
    }

    void runAll(const std::vector<std::string>& descriptions, const std::vector<double>& costs,
                const Job& job, const ResultSink& onResult) override
    {
        if (!isRoot() || mFinished)
            throw std::logic_error("runAll: only rank 0 hands out runs, and only before finish");
        std::vector<double> sizes = costs;
        sizes.resize(descriptions.size(), 0.0);
        const std::vector<size_t> order = largestFirst(sizes);

        // Rank 0's own share: a thread that takes the next largest run whenever it is free.
        std::mutex mutex;
        size_t next = 0;
        std::deque<Outcome> doneHere;
        auto take = [&]() -> std::optional<size_t> {
            std::lock_guard<std::mutex> lock(mutex);
            if (next == order.size()) return std::nullopt;
            return order[next++];
        };
        std::thread here([&] {
            while (const std::optional<size_t> i = take()) {
                Outcome o = runOne(job, *i, descriptions[*i], 0);
                std::lock_guard<std::mutex> lock(mutex);
                doneHere.push_back(std::move(o));
            }
        });

        // Everything below may fail (a run's error, a file rank 0 cannot write): then the job
        // ends here, with the message, rather than waiting hours for runs still going.
        try {
            auto handOut = [&](int worker) {
                if (const std::optional<size_t> i = take())
                    send(ByteWriter<>().integer(static_cast<long long>(*i)).text(descriptions[*i]).bytes(),
                         worker, kTagRun);
            };
            for (int worker = 1; worker < mRanks; ++worker) handOut(worker);
            for (size_t received = 0; received < descriptions.size();) {
                std::optional<Outcome> outcome;
                {
                    std::lock_guard<std::mutex> lock(mutex);
                    if (!doneHere.empty()) {
                        outcome = std::move(doneHere.front());
                        doneHere.pop_front();
                    }
                }
                if (!outcome) {
                    if (const std::optional<MPI_Status> s = waiting(MPI_ANY_SOURCE, kTagResult)) {
                        const std::string message = receive(*s);
                        handOut(s->MPI_SOURCE);  // keep it busy while this result is used
                        ByteReader in(message);
                        outcome = Outcome{size_t(in.integer()), s->MPI_SOURCE, Status(in.integer()), {}};
                        outcome->bytes = in.text();
                    }
                }
                if (!outcome) {
                    std::this_thread::sleep_for(kPollInterval);
                    continue;
                }
                ++received;
                if (outcome->status != Status::Done)
                    abortJob(outcome->status == Status::BadInput ? 1 : 3,
                             std::string(outcome->status == Status::BadInput ? "error" : "internal error") +
                                 ": run " + std::to_string(outcome->index + 1) + " of " +
                                 std::to_string(descriptions.size()) + " (on rank " +
                                 std::to_string(outcome->rank) + "): " + outcome->bytes);
                onResult(outcome->index, outcome->rank, outcome->bytes);
            }
        } catch (const Error& e) {
            abortJob(1, std::string("error: ") + e.what());
        } catch (const std::exception& e) {
            abortJob(3, std::string("internal error: ") + e.what());
        }
        here.join();
    }

    void serve(const Job& job) override
    {
        for (;;) {
            std::optional<MPI_Status> s;
            while (!(s = waiting(0, MPI_ANY_TAG))) std::this_thread::sleep_for(kPollInterval);
            const std::string message = receive(*s);
            if (s->MPI_TAG == kTagStop) return;
            ByteReader in(message);
            const size_t index = size_t(in.integer());
            Outcome o = runOne(job, index, in.text(), mRank);
            if (o.bytes.size() > size_t(INT_MAX) - 64) {
                // Rank 0 waits for every result: it must hear of this one too.
                o.status = Status::Failed;
                o.bytes = "its result of " + std::to_string(o.bytes.size()) +
                          " bytes is too large for one MPI message";
            }
            send(ByteWriter<>()
                     .integer(static_cast<long long>(o.index))
                     .integer(static_cast<long long>(o.status))
                     .text(o.bytes)
                     .bytes(),
                 0, kTagResult);
        }
    }

    void finish() override
    {
        if (!isRoot() || mFinished) return;
        mFinished = true;
        for (int worker = 1; worker < mRanks; ++worker)
            MPI_Send(nullptr, 0, MPI_BYTE, worker, kTagStop, MPI_COMM_WORLD);
    }

private:
    /// Print @a message as the tools print errors and end every rank with @a exitCode.
    [[noreturn]] void abortJob(int exitCode, const std::string& message) const
    {
        std::fflush(stdout);
        std::fprintf(stderr, "%s: %s\n", mToolName.c_str(), message.c_str());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, exitCode);
        std::abort();  // MPI_Abort does not return; this tells the compiler so
    }

    std::string mToolName;
    int mRank = 0, mRanks = 1, mRanksHere = 1;
    bool mFinished = false;
};

} // namespace

std::unique_ptr<RunDistributor> makeMpiRunDistributor(int& argc, char**& argv,
                                                      const std::string& toolName)
{
    return std::make_unique<MpiRunDistributor>(argc, argv, toolName);
}

} // namespace lsdem
