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

} // namespace

SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun,
                             RunDistributor& ranks)
{
    checkSlabStudyOptions(o);
    const auto start = SteadyClock::now();
    const SlabPanel panel(o.panel);
    const std::string assetDir = o.outDir + "/assets";
    // One process: the runs print their progress as they go and save their blocks. Several
    // ranks: a run's block and its lines travel to rank 0 with its result.
    const bool live = ranks.ranks() == 1;

    // The block of this rank's last run, kept for its next run at the same discretization
    // (one block in memory at a time).
    SlabCase bakedFor{Formulation::Adapted, -1.0, -1.0};
    std::shared_ptr<const GrainAsset> block;
    const RunDistributor::Job job = [&](const std::string& description) {
        ByteReader in(description);
        const Formulation f = Formulation(in.integer());
        const double sdp = in.number(), vdp = in.number();
        std::ostringstream buffer;
        std::ostream* out = live ? log : log ? &buffer : nullptr;
        std::string blockBytes;
        const auto bakeStart = SteadyClock::now();
        if (!(bakedFor.sdp == sdp && bakedFor.vdp == vdp)) {
            block.reset();
            block = bakeSlabBlock(panel, vdp, sdp);
            bakedFor = {f, sdp, vdp};
            if (live)
                saveAsset(*block, blockFileName(assetDir, sdp, vdp));
            else
                blockBytes = assetFileBytes(*block);
            if (out)
                *out << "  baked SDP " << sdp << " mm, VDP " << vdp << " mm: " << block->nodes.size()
                     << " nodes per block (mean spacing " << std::setprecision(3)
                     << block->spacing.mean << " mm) in " << secondsSince(bakeStart) << " s\n"
                     << std::flush;
        }
        const double bakeSeconds = secondsSince(bakeStart);
        if (out) *out << "  " << formulationName(f) << ", SDP " << sdp << ", VDP " << vdp << ": " << std::flush;
        SlabRunResult r = runSlabCase(o, panel, block, f, sdp, vdp, [&](double d) {
            if (live && out) *out << "δ = " << std::setprecision(3) << d << " mm ... " << std::flush;
        });
        r.bakeSeconds = bakeSeconds;
        if (out) {
            double peak = 0;
            for (const SlabSample& s : r.curve) peak = std::max(peak, s.force);
            *out << r.steps << " steps of " << std::setprecision(3) << r.dt << " s in "
                 << r.runSeconds << " s, peak P = " << peak << " N"
                 << (r.stopped ? " (STOPPED: " + r.error + ")" : "")
                 << (live ? "" : " (rank " + std::to_string(ranks.rank()) + ")") << "\n"
                 << std::flush;
        }
        ByteWriter<> record;
        writeSlabRunRecord(record, r);
        record.text(blockBytes).text(buffer.str());
        return record.bytes();
    };
    if (!ranks.isRoot()) {
        ranks.serve(job);
        return {};
    }
    std::filesystem::create_directories(assetDir);

    // The runs enter the result in the order a serial study makes them, whatever order they
    // finish in: `sequence` is that order, `entered` how far the result has got, `done` the
    // runs finished ahead of their turn.
    SlabStudyResult result;
    std::vector<Listed> sequence;
    size_t entered = 0;
    std::map<SlabCase, int> indexOf;
    std::map<SlabCase, SlabRunResult> done;
    std::set<std::string> blocksWritten;
    auto enterFinished = [&] {
        for (; entered < sequence.size(); ++entered) {
            const Listed& next = sequence[entered];
            if (indexOf.count(next.run)) continue;  // made already: the study shares it
            const auto it = done.find(next.run);
            if (it == done.end()) return;
            result.runs.push_back(std::move(it->second));
            result.stage.push_back(next.stage);
            indexOf[next.run] = int(result.runs.size()) - 1;
            done.erase(it);
            result.wallSeconds = secondsSince(start);
            if (afterEachRun) afterEachRun(result);
        }
    };
    // Make the runs of @a listed not made yet, spread over the ranks; their indices in the result.
    auto runListed = [&](const std::vector<Listed>& listed) {
        std::vector<SlabCase> todo;
        std::vector<std::string> descriptions;
        std::vector<double> costs;
        for (const Listed& l : listed) {
            sequence.push_back(l);
            if (indexOf.count(l.run) || std::find(todo.begin(), todo.end(), l.run) != todo.end())
                continue;
            todo.push_back(l.run);
            descriptions.push_back(ByteWriter<>()
                                       .integer(static_cast<long long>(l.run.formulation))
                                       .number(l.run.sdp)
                                       .number(l.run.vdp)
                                       .bytes());
            costs.push_back(slabRunCost(o, l.run).seconds);
        }
        ranks.runAll(descriptions, costs, job, [&](size_t i, int, const std::string& bytes) {
            ByteReader in(bytes);
            SlabRunResult r = readSlabRunRecord(in);
            const std::string blockBytes = in.text(), lines = in.text();
            const std::string name = blockFileName(assetDir, r.sdp, r.vdp);
            if (!blockBytes.empty() && blocksWritten.insert(name).second)
                writeStreamAtomically(name, [&](std::ostream& file) {
                    file.write(blockBytes.data(), std::streamsize(blockBytes.size()));
                });
            if (log) *log << lines << std::flush;
            done[todo[i]] = std::move(r);
            enterFinished();
        });
        enterFinished();  // runs all made before: nothing arrived to enter them
        std::vector<int> indices;
        for (const Listed& l : listed) indices.push_back(indexOf.at(l.run));
        return indices;
    };

    // Stage 1: SDP refined at fixed VDP, every formulation.
    const std::vector<double> sdps = slabCoarseToFine(o.sdps);
    if (log) *log << "stage 1: SDP refined at VDP = " << o.fixedVdp << " mm\n";
    const std::vector<SlabCase> stageOne = slabStageOneCases(o);
    std::vector<Listed> listed;
    for (const SlabCase& c : stageOne) listed.push_back({c, "sdp"});
    const std::vector<int> stageOneRuns = runListed(listed);
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
        std::vector<int> byVdp = runListed(listed);
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
