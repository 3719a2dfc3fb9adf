#include "FrameWriter.h"

#include "lsdem/ls/Inspection.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Micromechanics.h"
#include "lsdem/simulation/NonAffineMotion.h"

#include <Eigen/Geometry>

#include <cmath>

namespace lsdem {

FrameWriter::FrameWriter(const std::string& dir, const World& world,
                         const std::vector<RigidPose>* start)
    : mSeries(dir, kFramesBaseName)
{
    if (start) {
        mStart = *start;
        std::vector<double> radii;
        for (size_t i = 0; i < mStart.size(); ++i) {
            mStartPositions.push_back(mStart[i].position);
            radii.push_back(world.grains[i].asset->boundingRadius);
        }
        // Touching, or nearly, at the start.
        mStartNeighbours = neighboursWithin(mStartPositions, radii, 1.1);
    }
    // Surfaces at about the node spacing: as fine as the contact sees them, and light enough
    // for many grains and frames (at the level set's own voxels a frame of 27 spheres of 100
    // voxels across is 150 MB).
    for (const auto& asset : world.assets)
        if (!mSurfaces.count(asset.get()))
            mSurfaces[asset.get()] = zeroIsosurface(*asset->levelSet, asset->spacing.mean);
}

void FrameWriter::write(const Simulation& sim)
{
    const World& w = sim.world();
    // Split over ranks, each rank writes the grains it owns (and the forces on them) as its
    // piece of a parallel frame; otherwise the whole frame is written here.
    const GhostDecomposition* split = sim.ghosts();
    std::vector<VtkGrainMeasures> measures;
    if (!mStart.empty() && !split) {
        std::vector<Vec3> now;
        for (const Grain& g : w.grains) now.push_back(g.body.pose.position);
        const std::vector<double> d2 = nonAffineDisplacement(mStartPositions, now, mStartNeighbours);
        const std::vector<Mat3> stress = grainStresses(w, sim.contactRecords());
        for (size_t i = 0; i < w.grains.size(); ++i) {
            const RigidPose& p = w.grains[i].body.pose;
            const Eigen::AngleAxisd turned(p.orientation * mStart[i].orientation.conjugate());
            measures.push_back({p.position - mStart[i].position, std::abs(turned.angle()), d2[i],
                                stress[i]});
        }
    }
    std::vector<VtkGrain> grains;
    for (size_t i = 0; i < w.grains.size(); ++i) {
        const Grain& g = w.grains[i];
        if (split && !split->owned()[i]) continue;  // a ghost: its owner writes it
        const int id = split ? split->globalIds()[i] : static_cast<int>(i);
        grains.push_back({&mSurfaces.at(g.asset.get()), g.body.pose, id,
                          g.motion == GrainMotion::Fixed ? Vec3::Zero() : g.body.velocity,
                          g.angularVelocity(), measures.empty() ? nullptr : &measures[i]});
    }
    std::vector<VtkForcePoint> forces;
    // (Split over ranks, the simulation records the forces on owned grains only.)
    for (const ContactForceRecord& f : sim.contactForces())
        forces.push_back({f.point, f.force, f.grain});
    if (split)
        mSeries.writeParallelFrame(mSeries.framesWritten(), w.time, split->rank(),
                                   split->rankCount(), grains, forces);
    else
        mSeries.writeFrame(mSeries.framesWritten(), w.time, grains, forces);
}

} // namespace lsdem
