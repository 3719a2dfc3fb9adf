#include "studies/SlabStudy.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/ls/Stopwatch.h"

#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace lsdem {

SlabStudyResult runSlabStudy(const SlabStudyOptions& o, std::ostream* log,
                             const std::function<void(const SlabStudyResult&)>& afterEachRun)
{
    namespace fs = std::filesystem;
    checkSlabStudyOptions(o);
    const auto start = SteadyClock::now();
    const SlabPanel panel(o.panel);
    SlabStudyResult result;
    const std::string assetDir = o.outDir + "/assets";
    fs::create_directories(assetDir);

    // Baked blocks by (SDP, VDP), each saved so that the scenes (and lsdem-run) can read it.
    std::map<std::pair<double, double>, std::pair<std::shared_ptr<const GrainAsset>, std::string>> baked;
    auto blockFor = [&](double sdp, double vdp) {
        const auto key = std::make_pair(sdp, vdp);
        auto it = baked.find(key);
        if (it != baked.end()) return it->second;
        const auto t0 = SteadyClock::now();
        auto asset = bakeSlabBlock(panel, vdp, sdp);
        std::ostringstream name;
        name << assetDir << "/block_sdp" << sdp << "_vdp" << vdp << ".vdb";
        saveAsset(*asset, name.str());
        if (log)
            *log << "  baked SDP " << sdp << " mm, VDP " << vdp << " mm: " << asset->nodes.size()
                 << " nodes per block (mean spacing " << std::setprecision(3)
                 << asset->spacing.mean << " mm) in " << secondsSince(t0) << " s\n"
                 << std::flush;
        baked.clear();  // one block in memory at a time
        return baked[key] = {asset, name.str()};
    };
    auto run = [&](Formulation f, double sdp, double vdp, const std::string& stage) {
        for (size_t k = 0; k < result.runs.size(); ++k) {
            const SlabRunResult& r = result.runs[k];
            if (r.formulation == f && r.sdp == sdp && r.vdp == vdp) return int(k);
        }
        const auto bakeStart = SteadyClock::now();
        const auto [asset, path] = blockFor(sdp, vdp);
        const double bakeSeconds = secondsSince(bakeStart);
        if (log)
            *log << "  " << formulationName(f) << ", SDP " << sdp << ", VDP " << vdp << ": "
                 << std::flush;
        SlabRunResult r = runSlabCase(o, panel, asset, f, sdp, vdp, [&](double d) {
            if (log) *log << "δ = " << std::setprecision(3) << d << " mm ... " << std::flush;
        });
        r.bakeSeconds = bakeSeconds;
        if (log) {
            double peak = 0;
            for (const SlabSample& s : r.curve) peak = std::max(peak, s.force);
            *log << r.steps << " steps of " << std::setprecision(3) << r.dt << " s in "
                 << r.runSeconds << " s, peak P = " << peak << " N"
                 << (r.stopped ? " (STOPPED: " + r.error + ")" : "") << "\n"
                 << std::flush;
        }
        result.runs.push_back(std::move(r));
        result.stage.push_back(stage);
        result.wallSeconds = secondsSince(start);
        if (afterEachRun) afterEachRun(result);
        return int(result.runs.size()) - 1;
    };

    // Stage 1: SDP refined at fixed VDP, every formulation.
    const std::vector<double> sdps = slabCoarseToFine(o.sdps);
    if (log) *log << "stage 1: SDP refined at VDP = " << o.fixedVdp << " mm\n";
    std::vector<int> adaptedBySdp;
    for (double s : sdps)
        for (Formulation f : o.formulations) {
            if (!slabStageOneRuns(o, f, s)) continue;
            const int k = run(f, s, o.fixedVdp, "sdp");
            result.sdpSeries[f].push_back(k);
            if (f == Formulation::Adapted) adaptedBySdp.push_back(k);
        }

    const int sdpRun = slabConvergedRun(panel, result.runs, adaptedBySdp, o.tolerance, result.sdpConverged);
    result.convergedSdp = sdpRun >= 0 ? result.runs[sdpRun].sdp : sdps.back();
    result.convergedVdp = o.fixedVdp;
    result.convergedRun = sdpRun;

    if (o.twoWay && sdpRun >= 0) {
        const std::vector<double> vdps = slabCoarseToFine(o.vdps);
        if (log)
            *log << "stage 2: VDP refined at SDP = " << result.convergedSdp << " mm (adapted)\n";
        std::vector<int> byVdp;
        for (double v : vdps) byVdp.push_back(run(Formulation::Adapted, result.convergedSdp, v, "vdp"));
        result.vdpSeries = byVdp;
        const int vdpRun = slabConvergedRun(panel, result.runs, byVdp, o.tolerance, result.vdpConverged);
        result.convergedVdp = result.runs[vdpRun].vdp;
        result.convergedRun = vdpRun;
        // The coarse case of the snapshots: coarsest SDP and coarsest VDP.
        result.coarseRun = run(Formulation::Adapted, sdps.front(), vdps.front(), "coarse");
    } else if (!adaptedBySdp.empty()) {
        result.coarseRun = adaptedBySdp.front();
    }
    result.wallSeconds = secondsSince(start);
    return result;
}

} // namespace lsdem
