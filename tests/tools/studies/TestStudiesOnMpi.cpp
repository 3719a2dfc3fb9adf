// lsdem-study under `mpirun --oversubscribe -n 3` as a user runs it: each study spread over
// three ranks writes, from rank 0 alone, the files of the same study run in one process, byte
// for byte (a run's numbers do not depend on where it ran: the same code on the same inputs,
// deterministic on any thread count, its result sent back bit for bit). Skipped when lsdem was
// built without MPI. Open MPI refuses to start as root without OMPI_ALLOW_RUN_AS_ROOT*: ctest
// sets those for this program (tests/CMakeLists.txt), not the user's shell.
#include "studies/RunDistributor.h"

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using lsdem::test::runCommand;

using lsdem::test::readFile;

namespace {

const std::string kStudy = LSDEM_STUDY_EXE;
const std::string kMpiexec = LSDEM_MPIEXEC;

/// Every file under @a dir, relative to it.
std::set<std::string> filesUnder(const std::string& dir)
{
    std::set<std::string> names;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
        if (e.is_regular_file()) names.insert(std::filesystem::relative(e.path(), dir).string());
    return names;
}

/// Runs `lsdem-study ARGS --out DIR` in one process and under mpirun with 3 ranks.
struct SerialAndSpread
{
    lsdem::test::ScratchDir dir;
    std::string serial = dir.file("serial"), spread = dir.file("spread");
    lsdem::test::CommandResult one, three;

    explicit SerialAndSpread(const std::string& args)
    {
        one = runCommand(kStudy + " " + args + " --out '" + serial + "'");
        three = runCommand(kMpiexec + " --oversubscribe -n 3 " + kStudy + " " + args +
                           " --out '" + spread + "'");
    }
};

size_t count(const std::string& text, const std::string& what)
{
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// How many lines of @a text are exactly @a line.
size_t countLines(const std::string& text, const std::string& line)
{
    std::istringstream in(text);
    size_t n = 0;
    for (std::string l; std::getline(in, l);) n += l == line;
    return n;
}

/// The CSV text without the columns named in @a drop (run timings).
std::string withoutColumns(const std::string& csv, const std::set<std::string>& drop)
{
    std::istringstream in(csv);
    std::ostringstream out;
    std::vector<bool> keep;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') {
            out << line << '\n';
            continue;
        }
        std::vector<std::string> cells;
        std::istringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
        if (keep.empty())
            for (const std::string& name : cells) keep.push_back(!drop.count(name));
        for (size_t i = 0; i < cells.size(); ++i)
            if (i >= keep.size() || keep[i]) out << cells[i] << ',';
        out << '\n';
    }
    return out.str();
}

#define SKIP_WITHOUT_MPI()                                                                      \
    if (!lsdem::builtWithMpi() || kMpiexec.empty()) GTEST_SKIP() << "built without MPI"

} // namespace

TEST(StudiesOnMpi, TwoSpheresOverThreeRanksWritesTheSerialCsv)
{
    SKIP_WITHOUT_MPI();
    // Three node counts: three runs, one per rank at most.
    SerialAndSpread s("two-spheres --nodes 200 300 600 --steps 4 --orientations 2 --voxel 0.15 "
                      "--no-plots");
    ASSERT_EQ(s.one.exitCode, 0) << s.one.output;
    ASSERT_EQ(s.three.exitCode, 0) << s.three.output;
    EXPECT_EQ(readFile(s.spread + "/two_spheres.csv"), readFile(s.serial + "/two_spheres.csv"));
    EXPECT_EQ(filesUnder(s.spread), filesUnder(s.serial));
    EXPECT_NE(s.three.output.find("spread over 3 ranks"), std::string::npos) << s.three.output;
    EXPECT_NE(s.three.output.find("3 runs over 3 ranks"), std::string::npos) << s.three.output;
    // Only rank 0 prints: the summary once, each node count's bake line once.
    EXPECT_EQ(count(s.three.output, "wrote "), 1u) << s.three.output;
    EXPECT_EQ(count(s.three.output, "N = 300: baked"), 1u) << s.three.output;
}

TEST(StudiesOnMpi, Cube27OverThreeRanksWritesTheSerialCsv)
{
    SKIP_WITHOUT_MPI();
    // Eight runs of two sizes: more runs than ranks, handed out as ranks come free.
    SerialAndSpread s("cube27 --formulation adapted --nodes 300 600 --kn 500 1000 --voxel 0.3 "
                      "--periods 20 --orientations 2 --points 5 --no-plots");
    ASSERT_EQ(s.one.exitCode, 0) << s.one.output;
    ASSERT_EQ(s.three.exitCode, 0) << s.three.output;
    EXPECT_EQ(readFile(s.spread + "/cube27.csv"), readFile(s.serial + "/cube27.csv"));
    EXPECT_EQ(filesUnder(s.spread), filesUnder(s.serial));
    EXPECT_NE(s.three.output.find("8 runs over 3 ranks"), std::string::npos) << s.three.output;
    EXPECT_EQ(count(s.three.output, "wrote "), 1u) << s.three.output;
}

// The slab's two stages (stage 2 needs stage 1's converged SDP), both formulations, runs
// sharing a block across ranks: the same files, the blocks baked elsewhere written by rank 0.
// slab_runs.csv holds each run's bake and run time, which differ between any two runs of the
// program; every other column and file must be the same bytes.
TEST(StudiesOnMpi, SlabOverThreeRanksWritesTheSerialFiles)
{
    SKIP_WITHOUT_MPI();
    SerialAndSpread s("slab --blocks 3 --sdp 1 0.7 --vdp-fixed 0.3 --vdp 0.6 0.3 --delta-max 0.3 "
                      "--formulation adapted original --samples 20 --no-plots");
    ASSERT_EQ(s.one.exitCode, 0) << s.one.output;
    ASSERT_EQ(s.three.exitCode, 0) << s.three.output;
    for (const char* f : {"slab.csv", "slab_snapshots.csv", "slab_failure.txt", "slab_scene.toml",
                          "slab_block.obj"})
        EXPECT_EQ(readFile(s.spread + "/" + f), readFile(s.serial + "/" + f)) << f;
    const std::set<std::string> timings = {"bake_s", "run_s"};
    EXPECT_EQ(withoutColumns(readFile(s.spread + "/slab_runs.csv"), timings),
              withoutColumns(readFile(s.serial + "/slab_runs.csv"), timings));
    // The same files, the baked blocks included (their .vdb differ in OpenVDB's file id only).
    EXPECT_EQ(filesUnder(s.spread), filesUnder(s.serial));
    EXPECT_EQ(count(s.three.output, "VDP/SDP ="), 1u) << s.three.output;
    EXPECT_NE(s.three.output.find("on 3 MPI ranks"), std::string::npos) << s.three.output;
}

// Bad input under mpirun: every rank sees it, rank 0 alone says so, the job exits 1 and
// nothing is written.
TEST(StudiesOnMpi, BadInputIsReportedOnceAndNothingIsWritten)
{
    SKIP_WITHOUT_MPI();
    lsdem::test::ScratchDir dir;
    const auto r = runCommand(kMpiexec + " --oversubscribe -n 3 " + kStudy +
                              " two-spheres --radius -5 --out '" + dir.file("out") + "'");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(count(r.output, "--radius must be positive"), 1u) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// The distributor itself (tests/tools/studies/RunDistributorProbe.cpp: run i costs i and
// returns i², rank 0 prints each result as it arrives).
namespace {

struct ProbeResult
{
    size_t index;
    long long square, doneBy;
    int reportedRank;
};

std::vector<ProbeResult> probeResults(const std::string& output)
{
    std::vector<ProbeResult> results;
    std::istringstream in(output);
    for (std::string word; in >> word;)
        if (word == "result") {
            ProbeResult r{};
            in >> r.index >> r.square >> r.doneBy >> r.reportedRank;
            results.push_back(r);
        }
    return results;
}

} // namespace

// One rank under mpirun: rank 0's own thread takes the runs one by one, largest cost first.
TEST(StudiesOnMpi, OneRankDoesTheLargestRunsFirst)
{
    SKIP_WITHOUT_MPI();
    const auto r = runCommand(kMpiexec + " -n 1 " + std::string(LSDEM_PROBE_EXE) + " 5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::vector<size_t> order;
    for (const ProbeResult& p : probeResults(r.output)) order.push_back(p.index);
    EXPECT_EQ(order, (std::vector<size_t>{4, 3, 2, 1, 0})) << r.output;
}

// Three ranks, more runs than ranks: every run done exactly once, its result whole and
// credited to the rank that did it, every rank used, rank 0 alone printing.
TEST(StudiesOnMpi, EveryRunOnceOnSomeRank)
{
    SKIP_WITHOUT_MPI();
    const auto r = runCommand(kMpiexec + " --oversubscribe -n 3 " + std::string(LSDEM_PROBE_EXE) + " 12");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::vector<int> seen(12, 0);
    std::set<long long> ranksUsed;
    for (const ProbeResult& p : probeResults(r.output)) {
        ASSERT_LT(p.index, 12u);
        ++seen[p.index];
        EXPECT_EQ(p.square, static_cast<long long>(p.index * p.index));
        EXPECT_EQ(p.doneBy, p.reportedRank);
        ranksUsed.insert(p.doneBy);
    }
    EXPECT_EQ(seen, std::vector<int>(12, 1)) << r.output;
    EXPECT_EQ(ranksUsed.size(), 3u) << r.output;  // each run takes 20 ms: all ranks get some
    EXPECT_EQ(countLines(r.output, "done"), 1u) << r.output;
}

// A run that fails on whichever rank: the job ends (no rank waits for ever) with the tools'
// exit code for bad input, and rank 0 says which run failed and why, once.
TEST(StudiesOnMpi, AFailedRunEndsTheJobWithItsMessage)
{
    SKIP_WITHOUT_MPI();
    const auto r = runCommand(kMpiexec + " --oversubscribe -n 3 " + std::string(LSDEM_PROBE_EXE) + " 12 7");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(count(r.output, "probe: error: run 8 of 12 (on rank "), 1u) << r.output;
    EXPECT_NE(r.output.find("run 7 cannot be done"), std::string::npos) << r.output;
    EXPECT_EQ(countLines(r.output, "done"), 0u) << r.output;
}
