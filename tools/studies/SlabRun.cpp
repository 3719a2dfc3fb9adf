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

namespace {

/// What a slab run measures as the indenter goes down, from the grains' rest poses: the P–δ
/// curve's samples and the snapshots of every block.
class SlabRecorder
{
public:
    SlabRecorder(const Simulation& sim, const SlabPanel& panel, const GrainAsset& block)
        : mSim(sim), mPanel(panel), mIndenter(static_cast<int>(sim.world().boundaries.size()) - 1),
          mCentre(panel.centralBlock()),
          // The reference block's origin in the asset frame: where a block's rest centre goes.
          mOrigin(-(block.inputFrame.rotation * block.inputFrame.centroid))
    {
        for (const Grain& g : sim.world().grains) {
            mRestPosition.push_back(g.body.pose.position);
            mRestOrientation.push_back(g.body.pose.orientation);
        }
    }

    /// How far the indenter has gone down.
    double delta() const { return -world().boundaries[size_t(mIndenter)].displacement.z(); }

    SlabSample sample(double delta) const
    {
        const World& w = world();
        SlabSample s;
        s.delta = delta;
        s.force = w.boundaries[size_t(mIndenter)].force.z();
        s.centralDrop = -displacement(mCentre).z();
        for (int k = 0; k < count(); ++k)
            if (k != mCentre) s.othersMax = std::max(s.othersMax, displacement(k).norm());
        for (int b = 0; b < mIndenter; ++b) s.frameForce -= w.boundaries[size_t(b)].force.z();
        s.kinetic = mSim.energies().kinetic;
        return s;
    }

    SlabSnapshot snapshot(double delta) const
    {
        SlabSnapshot s;
        s.delta = delta;
        for (int k = 0; k < count(); ++k) {
            const RigidPose& pose = world().grains[size_t(k)].body.pose;
            s.displacement.push_back(displacement(k));
            const Mat3 turn = (pose.orientation * mRestOrientation[size_t(k)].conjugate()).toRotationMatrix();
            s.faces.push_back(mPanel.faces(mPanel.blocks()[size_t(k)], turn, pose.toWorld(mOrigin)));
        }
        return s;
    }

    std::vector<Vec3> displacements() const
    {
        std::vector<Vec3> d;
        for (int k = 0; k < count(); ++k) d.push_back(displacement(k));
        return d;
    }

private:
    const World& world() const { return mSim.world(); }
    int count() const { return static_cast<int>(mRestPosition.size()); }
    Vec3 displacement(int k) const
    {
        return world().grains[size_t(k)].body.pose.position - mRestPosition[size_t(k)];
    }

    const Simulation& mSim;
    const SlabPanel& mPanel;
    int mIndenter, mCentre;
    Vec3 mOrigin;
    std::vector<Vec3> mRestPosition;
    std::vector<Quat> mRestOrientation;
};

} // namespace

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
    Simulation sim(buildWorld(scene, warnings), r.dt);
    const SlabRecorder recorder(sim, panel, *block);

    const double deltaMax = slabDeltaMax(o);
    const long long totalSteps = static_cast<long long>(std::ceil(deltaMax / (o.speed * r.dt)));
    const long long recordEvery = std::max<long long>(1, totalSteps / o.samples);
    const std::vector<double> targets = slabSnapshotDeltas(o);
    size_t nextSnapshot = 0;
    auto takeSnapshots = [&](double d) {
        while (nextSnapshot < targets.size() && d >= targets[nextSnapshot] - 1e-9 * deltaMax) {
            r.snapshots.push_back(recorder.snapshot(d));
            ++nextSnapshot;
        }
    };

    r.curve.push_back(recorder.sample(0.0));
    takeSnapshots(0.0);
    SteadyClock::time_point lastReport = SteadyClock::now();
    try {
        while (recorder.delta() < deltaMax * (1.0 - 1e-12)) {
            sim.step();
            ++r.steps;
            const double d = recorder.delta();
            if (r.steps % recordEvery == 0 || d >= deltaMax * (1.0 - 1e-12))
                r.curve.push_back(recorder.sample(d));
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
        const double d = recorder.delta();
        if (r.curve.empty() || r.curve.back().delta != d) r.curve.push_back(recorder.sample(d));
    }
    r.finalDisplacement = recorder.displacements();
    r.nodeChecks = sim.counters().nodes.nodesConsidered;
    r.stabilityLimit = sim.stabilityLimitSeen();
    r.runSeconds = wall.seconds();
    return r;
}

} // namespace lsdem
