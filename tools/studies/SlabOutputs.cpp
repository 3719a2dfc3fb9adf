// The files a slab study writes: the P–δ curves, one row per run, the snapshots, the failure
// summary and the converged case as a scene for lsdem-run.
#include "studies/SlabStudy.h"

#include "lsdem/core/NumberText.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/AtomicFile.h"
#include "lsdem/mesh/MeshIO.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace lsdem {

namespace {

/// The comment line every CSV of the study starts with: the panel, the indenter and the law.
std::string slabHeader(const SlabStudyOptions& o)
{
    const SlabStiffness k = slabStiffness(o);
    std::ostringstream head;
    head << "# lsdem slab study: " << o.panel.blocksPerSide << "x" << o.panel.blocksPerSide
         << " blocks, L=" << o.panel.blockSize << " mm, t=" << o.panel.thickness
         << " mm, angle=" << o.panel.angleDeg << " deg, indenter R=" << o.indenterRadius
         << " mm at " << o.speed << " mm/s; kn*=" << k.knStar << " N/mm^3, ks*=" << k.ksStar
         << " N/mm^3, kn=" << k.kn << " N/mm, ks=" << k.ks << " N/mm, mu=" << o.material.friction
         << ", testing=" << nodeTestingName(o.testing) << "; force in N, lengths in mm\n";
    return head.str();
}

/// slab.csv: every run's P–δ curve.
void writeSlabCurves(const SlabStudyResult& result, const SlabStudyOptions& o,
                     const std::string& head)
{
    std::ostringstream curves;
    curves << std::setprecision(10) << head
           << "run,formulation,sdp,vdp,nodes,delta,P,central_drop,others_max,frame_force,kinetic\n";
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const SlabRunResult& r = result.runs[i];
        for (const SlabSample& s : r.curve)
            curves << i << ',' << formulationName(r.formulation) << ',' << r.sdp << ',' << r.vdp
                   << ',' << r.nodes << ',' << s.delta << ',' << s.force << ',' << s.centralDrop
                   << ',' << s.othersMax << ',' << s.frameForce << ',' << s.kinetic << '\n';
    }
    writeTextFileAtomically(o.outDir + "/slab.csv", curves.str());

}

/// slab_runs.csv: each run, against the finest of its refinement series (stage 1 of its
/// formulation, and stage 2); empty where it is not a member.
void writeSlabRuns(const SlabStudyResult& result, const SlabStudyOptions& o, const SlabPanel& panel,
                   const std::string& head)
{
    std::ostringstream runs;
    runs << std::setprecision(10) << head
         << "run,stage,role,formulation,sdp,vdp,vdp_over_sdp,nodes,spacing_measured,stiffness,dt,"
            "stability_limit,steps,bake_s,run_s,node_checks,P_max,delta_at_P_max,central_drop,"
            "others_max,diff_sdp_series,diff_vdp_series,diff_whole_curve,failure_mode,stopped\n";
    auto seriesDifference = [&](const std::vector<int>& series, int i, bool whole) {
        if (std::find(series.begin(), series.end(), i) == series.end()) return std::string();
        return roundedText(slabCurveDifference(result.runs[i].curve, result.runs[series.back()].curve, whole));
    };
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const SlabRunResult& r = result.runs[i];
        const auto own = result.sdpSeries.find(r.formulation);
        const std::vector<int> none;
        const std::vector<int>& sdpSeries = own != result.sdpSeries.end() ? own->second : none;
        const std::string diffSdp = seriesDifference(sdpSeries, int(i), false);
        const std::string diffVdp = seriesDifference(result.vdpSeries, int(i), false);
        std::string whole = seriesDifference(sdpSeries, int(i), true);
        if (whole.empty()) whole = seriesDifference(result.vdpSeries, int(i), true);
        double peak = 0, at = 0;
        for (const SlabSample& s : r.curve)
            if (s.force > peak) {
                peak = s.force;
                at = s.delta;
            }
        const std::string role = int(i) == result.convergedRun ? "converged"
                                 : int(i) == result.coarseRun  ? "coarse"
                                                               : "";
        runs << i << ',' << result.stage[i] << ',' << role << ',' << formulationName(r.formulation)
             << ',' << r.sdp << ',' << r.vdp << ',' << r.vdp / r.sdp << ',' << r.nodes << ','
             << r.meanSpacing << ',' << r.stiffness << ',' << r.dt << ',' << r.stabilityLimit << ','
             << r.steps << ','
             << r.bakeSeconds << ',' << r.runSeconds << ',' << r.nodeChecks << ',' << peak << ','
             << at << ',' << (r.curve.empty() ? 0.0 : r.curve.back().centralDrop) << ','
             << (r.curve.empty() ? 0.0 : r.curve.back().othersMax) << ',' << diffSdp << ','
             << diffVdp << ',' << whole
             << ',' << slabFailureModeName(slabFailureMode(panel, r)) << ',' << (r.stopped ? 1 : 0)
             << '\n';
    }
    writeTextFileAtomically(o.outDir + "/slab_runs.csv", runs.str());

}

/// slab_snapshots.csv: every face of every block of the coarse and the converged runs.
void writeSlabSnapshots(const SlabStudyResult& result, const SlabStudyOptions& o,
                        const SlabPanel& panel, const std::string& head)
{
    auto label = [](const SlabRunResult& r) {
        std::ostringstream s;
        s << formulationName(r.formulation) << " SDP " << r.sdp << " VDP " << r.vdp;
        return s.str();
    };

    std::ostringstream snaps;
    snaps << std::setprecision(8) << head
          << "run,role,label,delta,block,i,j,displacement,face,x0,y0,z0,x1,y1,z1,x2,y2,z2,x3,y3,z3\n";
    for (int i : {result.coarseRun, result.convergedRun}) {
        if (i < 0) continue;
        const SlabRunResult& r = result.runs[i];
        const std::string role = i == result.convergedRun ? "converged" : "coarse";
        for (const SlabSnapshot& s : r.snapshots)
            for (size_t b = 0; b < s.faces.size(); ++b)
                for (int f = 0; f < 6; ++f) {
                    snaps << i << ',' << role << ',' << label(r) << ',' << s.delta << ','
                          << panel.blocks()[b].name << ',' << panel.blocks()[b].i << ','
                          << panel.blocks()[b].j << ',' << s.displacement[b].norm() << ',' << f;
                    for (const Vec3& c : s.faces[b][f].corners)
                        snaps << ',' << c.x() << ',' << c.y() << ',' << c.z();
                    snaps << '\n';
                }
        if (result.coarseRun == result.convergedRun) break;
    }
    writeTextFileAtomically(o.outDir + "/slab_snapshots.csv", snaps.str());

}

/// slab_failure.txt: how the panel failed, per run.
void writeSlabFailure(const SlabStudyResult& result, const SlabStudyOptions& o,
                      const SlabPanel& panel)
{
    std::ostringstream text;
    text << "Failure of the panel at delta_max = " << slabDeltaMax(o) << " mm, per run\n\n";
    for (size_t i = 0; i < result.runs.size(); ++i) {
        const std::string role = int(i) == result.convergedRun ? " [converged]"
                                 : int(i) == result.coarseRun  ? " [coarse]"
                                                               : "";
        text << "run " << i << " (" << result.stage[i] << ")" << role << ": "
             << slabFailureSummary(panel, result.runs[i]) << "\n";
    }
    writeTextFileAtomically(o.outDir + "/slab_failure.txt", text.str());

}

} // namespace

void writeSlabOutputs(const SlabStudyResult& result, const SlabStudyOptions& o,
                      const SlabPanel& panel)
{
    const std::string head = slabHeader(o);
    writeSlabCurves(result, o, head);
    writeSlabRuns(result, o, panel, head);
    writeSlabSnapshots(result, o, panel, head);
    writeSlabFailure(result, o, panel);
    if (o.writeScene && result.convergedRun >= 0) {
        const SlabRunResult& r = result.runs[result.convergedRun];
        std::ostringstream name;
        name << o.outDir << "/assets/block_sdp" << r.sdp << "_vdp" << r.vdp << ".vdb";
        if (std::filesystem::exists(name.str())) {
            Scene scene = makeSlabScene(o, r.formulation, loadAsset(name.str()), r.dt);
            scene.assets.front().file = name.str();
            writeSlabScene(scene, o, o.outDir + "/slab_scene.toml");
        }
        writeMesh(panel.referenceMesh(), o.outDir + "/slab_block.obj");
    }
}

} // namespace lsdem
