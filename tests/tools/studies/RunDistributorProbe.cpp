// A program for TestStudiesOnMpi: the run distributor (tools/studies/RunDistributor.h) on runs
// that say who did them. `probe N [FAIL]`: N runs of cost i (run i), run FAIL throws
// lsdem::Error. Rank 0 prints each result as it arrives, "result <i> <i*i> <rank>", then
// "done"; the other ranks print nothing.
#include "studies/RunDistributor.h"
#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"

#include "lsdem/core/Error.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

int main(int argc, char** argv)
{
    using namespace lsdem;
    std::unique_ptr<RunDistributor> ranks = makeRunDistributor(argc, argv, "probe");
    const int runs = argc > 1 ? std::atoi(argv[1]) : 6;
    const int failing = argc > 2 ? std::atoi(argv[2]) : -1;
    const RunDistributor::Job job = [&](const std::string& description) {
        const long long i = ByteReader(description).integer();
        if (i == failing) throw Error("", "run " + std::to_string(i) + " cannot be done", "none");
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // let every rank ask
        return ByteWriter<>().integer(i * i).integer(ranks->rank()).bytes();
    };
    if (!ranks->isRoot()) {
        ranks->serve(job);
        return 0;
    }
    std::vector<std::string> descriptions;
    std::vector<double> costs;
    for (int i = 0; i < runs; ++i) {
        descriptions.push_back(ByteWriter<>().integer(i).bytes());
        costs.push_back(double(i));
    }
    ranks->runAll(descriptions, costs, job, [](size_t i, int rank, const std::string& result) {
        ByteReader in(result);
        const long long square = in.integer(), by = in.integer();
        std::printf("result %zu %lld %lld %d\n", i, square, by, rank);
        std::fflush(stdout);
    });
    ranks->finish();
    std::printf("done\n");
    return 0;
}
