#include "studies/SlabStudy.h"

#include "studies/SlabRunRecord.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Stopwatch.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

namespace lsdem {

namespace {

std::string blockFileName(const std::string& assetDir, double sdp, double vdp)
{
    std::ostringstream name;
    name << assetDir << "/block_sdp" << sdp << "_vdp" << vdp << ".vdb";
    return name.str();
}

/// The bytes of @a asset's .vdb file, for rank 0 to write: saved to a private temporary file
/// (OpenVDB writes files, not memory), read back and removed.
std::string assetFileBytes(const GrainAsset& asset)
{
    namespace fs = std::filesystem;
    const fs::path path = fs::temp_directory_path() /
                          ("lsdem-study-" + std::to_string(::getpid()) + "-block.vdb");
    saveAsset(asset, path.string());
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    fs::remove(path);
    return bytes;
}

/// A run of the serial study's sequence: its case and the stage it is first listed in.
struct Listed
{
    SlabCase run;
    std::string stage;
};

/// What a rank does with one run's description (formulation, SDP, VDP): bake the block, or
/// keep the last one if it has the same discretization (one block in memory at a time), run
/// the case, and return its record, with the block's file bytes and the progress lines when
/// it has to travel to rank 0.
class SlabRankWork
{
public:
    SlabRankWork(const SlabStudyOptions& o, const SlabPanel& panel, std::ostream* log,
                 const RunDistributor& ranks)
        : mOptions(o), mPanel(panel), mLog(log), mRanks(ranks), mLive(ranks.ranks() == 1),
          mAssetDir(o.outDir + "/assets")
    {
    }

    std::string operator()(const std::string& description)
    {
        ByteReader in(description);
        const Formulation f = Formulation(in.integer());
        const double sdp = in.number(), vdp = in.number();
        // One process: the run prints its progress as it goes and saves its block. Several
        // ranks: the block and the lines travel to rank 0 with the result.
        std::ostringstream buffer;
        std::ostream* out = mLive ? mLog : mLog ? &buffer : nullptr;
        const auto bakeStart = SteadyClock::now();
        const std::string blockBytes = bakeIfNew(f, sdp, vdp, out);
        const double bakeSeconds = secondsSince(bakeStart);
        if (out) *out << "  " << formulationName(f) << ", SDP " << sdp << ", VDP " << vdp << ": " << std::flush;
        SlabRunResult r = runSlabCase(mOptions, mPanel, mBlock, f, sdp, vdp, [&](double d) {
            if (mLive && out) *out << "δ = " << std::setprecision(3) << d << " mm ... " << std::flush;
        });
        r.bakeSeconds = bakeSeconds;
        if (out) report(*out, r);
        ByteWriter<> record;
        writeSlabRunRecord(record, r);
        record.text(blockBytes).text(buffer.str());
        return record.bytes();
    }

private:
    /// Bake the block of (@a sdp, @a vdp) unless it is the one held; saved (one process) or
    /// returned as file bytes (several ranks; empty if none was baked).
    std::string bakeIfNew(Formulation f, double sdp, double vdp, std::ostream* out)
    {
        if (mBakedFor.sdp == sdp && mBakedFor.vdp == vdp) return {};
        const auto start = SteadyClock::now();
        mBlock.reset();
        mBlock = bakeSlabBlock(mPanel, vdp, sdp);
        mBakedFor = {f, sdp, vdp};
        std::string bytes;
        if (mLive)
            saveAsset(*mBlock, blockFileName(mAssetDir, sdp, vdp));
        else
            bytes = assetFileBytes(*mBlock);
        if (out)
            *out << "  baked SDP " << sdp << " mm, VDP " << vdp << " mm: " << mBlock->nodes.size()
                 << " nodes per block (mean spacing " << std::setprecision(3)
                 << mBlock->spacing.mean << " mm) in " << secondsSince(start) << " s\n"
                 << std::flush;
        return bytes;
    }

    void report(std::ostream& out, const SlabRunResult& r) const
    {
        double peak = 0;
        for (const SlabSample& s : r.curve) peak = std::max(peak, s.force);
        out << r.steps << " steps of " << std::setprecision(3) << r.dt << " s in " << r.runSeconds
            << " s, peak P = " << peak << " N" << (r.stopped ? " (STOPPED: " + r.error + ")" : "")
            << (mLive ? "" : " (rank " + std::to_string(mRanks.rank()) + ")") << "\n"
            << std::flush;
    }

    const SlabStudyOptions& mOptions;
    const SlabPanel& mPanel;
    std::ostream* mLog;
    const RunDistributor& mRanks;
    bool mLive;
    std::string mAssetDir;
    SlabCase mBakedFor{Formulation::Adapted, -1.0, -1.0};
    std::shared_ptr<const GrainAsset> mBlock;
};

/// Rank 0's side: runs listed stage by stage, spread over the ranks, entering the result in
/// the order a serial study makes them, whatever order they finish in (`sequence` is that
/// order, `entered` how far the result has got, `done` the runs finished ahead of their turn);
/// a run listed again is not made again.
class SlabRunsInOrder
{
public:
    SlabRunsInOrder(const SlabStudyOptions& o, std::ostream* log, RunDistributor& ranks,
                    const RunDistributor::Job& job,
                    const std::function<void(const SlabStudyResult&)>& afterEachRun,
                    SteadyClock::time_point start, SlabStudyResult& result)
        : mOptions(o), mLog(log), mRanks(ranks), mJob(job), mAfterEachRun(afterEachRun),
          mStart(start), mResult(result), mAssetDir(o.outDir + "/assets")
    {
    }

    /// Make the runs of @a listed not made yet; their indices in the result.
    std::vector<int> run(const std::vector<Listed>& listed)
    {
        std::vector<SlabCase> todo;
        std::vector<std::string> descriptions;
        std::vector<double> costs;
        for (const Listed& l : listed) {
            mSequence.push_back(l);
            if (mIndexOf.count(l.run) || std::find(todo.begin(), todo.end(), l.run) != todo.end())
                continue;
            todo.push_back(l.run);
            descriptions.push_back(ByteWriter<>()
                                       .integer(static_cast<long long>(l.run.formulation))
                                       .number(l.run.sdp)
                                       .number(l.run.vdp)
                                       .bytes());
            costs.push_back(slabRunCost(mOptions, l.run).seconds);
        }
        mRanks.runAll(descriptions, costs, mJob, [&](size_t i, int, const std::string& bytes) {
            arrived(todo[i], bytes);
        });
        enterFinished();  // runs all made before: nothing arrived to enter them
        std::vector<int> indices;
        for (const Listed& l : listed) indices.push_back(mIndexOf.at(l.run));
        return indices;
    }

private:
    /// A run's record from its rank: its block file written once, its lines logged.
    void arrived(const SlabCase& run, const std::string& bytes)
    {
        ByteReader in(bytes);
        SlabRunResult r = readSlabRunRecord(in);
        const std::string blockBytes = in.text(), lines = in.text();
        const std::string name = blockFileName(mAssetDir, r.sdp, r.vdp);
        if (!blockBytes.empty() && mBlocksWritten.insert(name).second)
            writeStreamAtomically(name, [&](std::ostream& file) {
                file.write(blockBytes.data(), std::streamsize(blockBytes.size()));
            });
        if (mLog) *mLog << lines << std::flush;
        mDone[run] = std::move(r);
        enterFinished();
    }

    void enterFinished()
    {
        for (; mEntered < mSequence.size(); ++mEntered) {
            const Listed& next = mSequence[mEntered];
            if (mIndexOf.count(next.run)) continue;  // made already: the study shares it
            const auto it = mDone.find(next.run);
            if (it == mDone.end()) return;
            mResult.runs.push_back(std::move(it->second));
            mResult.stage.push_back(next.stage);
            mIndexOf[next.run] = int(mResult.runs.size()) - 1;
            mDone.erase(it);
            mResult.wallSeconds = secondsSince(mStart);
            if (mAfterEachRun) mAfterEachRun(mResult);
        }
    }

    const SlabStudyOptions& mOptions;
    std::ostream* mLog;
    RunDistributor& mRanks;
    const RunDistributor::Job& mJob;
    const std::function<void(const SlabStudyResult&)>& mAfterEachRun;
    SteadyClock::time_point mStart;
    SlabStudyResult& mResult;
    std::string mAssetDir;
    std::vector<Listed> mSequence;
    size_t mEntered = 0;
    std::map<SlabCase, int> mIndexOf;
    std::map<SlabCase, SlabRunResult> mDone;
    std::set<std::string> mBlocksWritten;
};

} // namespace

SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun,
                             RunDistributor& ranks)
{
    checkSlabStudyOptions(o);
    const auto start = SteadyClock::now();
    const SlabPanel panel(o.panel);
    SlabRankWork work(o, panel, log, ranks);
    const RunDistributor::Job job = [&](const std::string& description) { return work(description); };
    if (!ranks.isRoot()) {
        ranks.serve(job);
        return {};
    }
    std::filesystem::create_directories(o.outDir + "/assets");
    SlabStudyResult result;
    SlabRunsInOrder runs(o, log, ranks, job, afterEachRun, start, result);

    // Stage 1: SDP refined at fixed VDP, every formulation.
    const std::vector<double> sdps = slabCoarseToFine(o.sdps);
    if (log) *log << "stage 1: SDP refined at VDP = " << o.fixedVdp << " mm\n";
    const std::vector<SlabCase> stageOne = slabStageOneCases(o);
    std::vector<Listed> listed;
    for (const SlabCase& c : stageOne) listed.push_back({c, "sdp"});
    const std::vector<int> stageOneRuns = runs.run(listed);
    std::vector<int> adaptedBySdp;
    for (size_t i = 0; i < stageOne.size(); ++i) {
        result.sdpSeries[stageOne[i].formulation].push_back(stageOneRuns[i]);
        if (stageOne[i].formulation == Formulation::Adapted) adaptedBySdp.push_back(stageOneRuns[i]);
    }

    const int sdpRun = slabConvergedRun(panel, result.runs, adaptedBySdp, o.tolerance, result.sdpConverged);
    result.convergedSdp = sdpRun >= 0 ? result.runs[sdpRun].sdp : sdps.back();
    result.convergedVdp = o.fixedVdp;
    result.convergedRun = sdpRun;

    if (o.twoWay && sdpRun >= 0) {
        if (log)
            *log << "stage 2: VDP refined at SDP = " << result.convergedSdp << " mm (adapted)\n";
        // The VDP series and the coarse case of the snapshots: coarsest SDP and coarsest VDP.
        listed.clear();
        for (const SlabCase& c : slabStageTwoCases(o, result.convergedSdp)) listed.push_back({c, "vdp"});
        listed.push_back({slabCoarseCase(o), "coarse"});
        std::vector<int> byVdp = runs.run(listed);
        result.coarseRun = byVdp.back();
        byVdp.pop_back();
        result.vdpSeries = byVdp;
        const int vdpRun = slabConvergedRun(panel, result.runs, byVdp, o.tolerance, result.vdpConverged);
        result.convergedVdp = result.runs[vdpRun].vdp;
        result.convergedRun = vdpRun;
    } else if (!adaptedBySdp.empty()) {
        result.coarseRun = adaptedBySdp.front();
    }
    ranks.finish();
    result.wallSeconds = secondsSince(start);
    return result;
}

} // namespace lsdem
