#include "studies/SlabRun.h"

#include "studies/SlabModel.h"
#include "studies/SlabScene.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

SlabRunResult runSlabCase(const SlabStudyOptions& o, const SlabPanel& panel,
                          std::shared_ptr<const GrainAsset> block, Formulation f, double sdp,
                          double vdp, const std::function<void(double)>& progress)
{
    const Stopwatch wall;
    SlabRunResult r;
    r.formulation = f;
    r.sdp = sdp;
    r.vdp = vdp;
    r.nodes = static_cast<int>(block->nodes.size());
    r.meanSpacing = block->spacing.mean;
    r.stiffness = slabContactModel(o, f).normalStiffness;
    r.dt = slabTimeStep(o, panel, *block, f);

    const Scene scene = makeSlabScene(o, f, block, r.dt);
    std::vector<std::string> warnings;
    World world = buildWorld(scene, warnings);
    Simulation sim(std::move(world), r.dt);
    const World& w = sim.world();
    const int indenter = static_cast<int>(w.boundaries.size()) - 1;
    const int centre = panel.centralBlock();
    const int count = static_cast<int>(w.grains.size());
    std::vector<Vec3> p0(count);
    std::vector<Quat> q0(count);
    for (int k = 0; k < count; ++k) {
        p0[k] = w.grains[k].body.pose.position;
        q0[k] = w.grains[k].body.pose.orientation;
    }
    // The reference block's origin in the asset frame: where a block's rest centre goes.
    const Vec3 origin = -(block->inputFrame.rotation * block->inputFrame.centroid);

    const double deltaMax = slabDeltaMax(o);
    const long long totalSteps = static_cast<long long>(std::ceil(deltaMax / (o.speed * r.dt)));
    const long long recordEvery = std::max<long long>(1, totalSteps / o.samples);
    const std::vector<double> targets = slabSnapshotDeltas(o);
    size_t nextSnapshot = 0;

    auto sample = [&](double delta) {
        SlabSample s;
        s.delta = delta;
        s.force = w.boundaries[indenter].force.z();
        s.centralDrop = -(w.grains[centre].body.pose.position - p0[centre]).z();
        for (int k = 0; k < count; ++k)
            if (k != centre)
                s.othersMax = std::max(s.othersMax, (w.grains[k].body.pose.position - p0[k]).norm());
        for (int b = 0; b < indenter; ++b) s.frameForce -= w.boundaries[b].force.z();
        s.kinetic = sim.energies().kinetic;
        r.curve.push_back(s);
    };
    auto snapshot = [&](double delta) {
        SlabSnapshot s;
        s.delta = delta;
        for (int k = 0; k < count; ++k) {
            const RigidPose& pose = w.grains[k].body.pose;
            s.displacement.push_back(pose.position - p0[k]);
            const Mat3 turn = (pose.orientation * q0[k].conjugate()).toRotationMatrix();
            s.faces.push_back(panel.faces(panel.blocks()[k], turn, pose.toWorld(origin)));
        }
        r.snapshots.push_back(std::move(s));
    };
    auto delta = [&] { return -w.boundaries[indenter].displacement.z(); };
    auto takeSnapshots = [&](double d) {
        while (nextSnapshot < targets.size() && d >= targets[nextSnapshot] - 1e-9 * deltaMax) {
            snapshot(d);
            ++nextSnapshot;
        }
    };

    sample(0.0);
    takeSnapshots(0.0);
    SteadyClock::time_point lastReport = SteadyClock::now();
    try {
        while (delta() < deltaMax * (1.0 - 1e-12)) {
            sim.step();
            ++r.steps;
            const double d = delta();
            if (r.steps % recordEvery == 0 || d >= deltaMax * (1.0 - 1e-12)) sample(d);
            takeSnapshots(d);
            if (progress && secondsSince(lastReport) > 10.0) {
                progress(d);
                lastReport = SteadyClock::now();
            }
        }
    } catch (const Error& e) {
        // Keep what was recorded; the caller reports the failure.
        r.stopped = true;
        r.error = e.what();
        if (r.curve.empty() || r.curve.back().delta != delta()) sample(delta());
    }
    for (int k = 0; k < count; ++k) r.finalDisplacement.push_back(w.grains[k].body.pose.position - p0[k]);
    r.nodeChecks = sim.counters().nodes.nodesConsidered;
    r.stabilityLimit = sim.stabilityLimitSeen();
    r.runSeconds = wall.seconds();
    return r;
}

} // namespace lsdem
