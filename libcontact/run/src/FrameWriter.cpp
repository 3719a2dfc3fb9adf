#include "FrameWriter.h"

#include "lsdem/ls/Inspection.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Micromechanics.h"
#include "lsdem/simulation/NonAffineMotion.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace lsdem {

FrameWriter::FrameWriter(const std::string& dir, const World& world,
                         const std::vector<RigidPose>* start, double spacing,
                         const Vec3& startCellSize)
    : mSeries(dir, kFramesBaseName), mMeasures(start != nullptr), mStartCellSize(startCellSize)
{
    if (start) {
        mStart = *start;
        for (const RigidPose& pose : mStart) mStartPositions.push_back(pose.position);
    }
    // Surfaces at about the node spacing: as fine as the contact sees them, and light enough
    // for many grains and frames (at the level set's own voxels a frame of 27 spheres of 100
    // voxels across is 150 MB); or at the scene's coarser frame_spacing for very many grains.
    for (const auto& asset : world.assets)
        if (!mSurfaces.count(asset.get()))
            mSurfaces[asset.get()] =
                zeroIsosurface(*asset->levelSet, spacing > 0.0 ? spacing : asset->spacing.mean);
}

std::vector<VtkGrainMeasures> FrameWriter::grainMeasures(const Simulation& sim)
{
    const GhostDecomposition* split = sim.ghosts();
    World gathered;
    if (split) gathered = sim.wholeWorld();
    const std::vector<ContactRecord> records = sim.wholeContactRecords();
    const World& whole = split ? gathered : sim.world();
    constexpr size_t kNumbers = 14;  // displacement, rotation, D²min, stress
    std::vector<double> packed;
    if (!split || split->rank() == 0) {
        if (!mNeighboursFound) {  // touching, or nearly, at the start
            std::vector<double> radii;
            for (const Grain& g : whole.grains) radii.push_back(g.asset->boundingRadius);
            // (In a periodic cell, with the images across the faces: the cell as it started.)
            PeriodicCell startCell = whole.periodic;
            startCell.size = mStartCellSize;
            mStartNeighbours = neighboursWithin(mStartPositions, radii, 1.1, startCell);
            mNeighboursFound = true;
        }
        std::vector<Vec3> now;  // (in a periodic cell, where the motion took them)
        for (const Grain& g : whole.grains) now.push_back(g.unwrappedPosition());
        const std::vector<double> d2 = nonAffineDisplacement(mStartPositions, mStartCellSize, now,
                                                             whole.periodic.size, mStartNeighbours);
        const std::vector<Mat3> stress = grainStresses(whole, records);
        for (size_t i = 0; i < whole.grains.size(); ++i) {
            const RigidPose& p = whole.grains[i].body.pose;
            const Eigen::AngleAxisd turned(p.orientation * mStart[i].orientation.conjugate());
            const Vec3 moved = whole.grains[i].unwrappedPosition() - mStart[i].position;
            packed.insert(packed.end(), {moved.x(), moved.y(), moved.z(), std::abs(turned.angle()),
                                         d2[i]});
            packed.insert(packed.end(), stress[i].data(), stress[i].data() + 9);
        }
    }
    packed = sim.numbersFromRankZero(packed);
    const World& w = sim.world();
    std::vector<VtkGrainMeasures> measures(w.grains.size());
    for (size_t i = 0; i < w.grains.size(); ++i) {
        const size_t id = split ? size_t(split->globalIds()[i]) : i;
        if ((id + 1) * kNumbers > packed.size()) continue;  // (never: every grain was measured)
        const double* m = packed.data() + id * kNumbers;
        VtkGrainMeasures& out = measures[i];
        out.displacement = Vec3(m[0], m[1], m[2]);
        out.rotation = m[3];
        out.d2min = m[4];
        std::copy(m + 5, m + 14, out.stress.data());
    }
    return measures;
}

void FrameWriter::write(const Simulation& sim)
{
    const World& w = sim.world();
    // Split over ranks, each rank writes the grains it owns (and the forces on them) as its
    // piece of a parallel frame; otherwise the whole frame is written here.
    const GhostDecomposition* split = sim.ghosts();
    std::vector<VtkGrainMeasures> measures;
    if (mMeasures) measures = grainMeasures(sim);
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
                                   split->rankCount(), grains, forces, mMeasures, w.membranes);
    else
        mSeries.writeFrame(mSeries.framesWritten(), w.time, grains, forces, w.membranes);
}

} // namespace lsdem
