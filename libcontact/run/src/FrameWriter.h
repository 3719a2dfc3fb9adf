// The ParaView output of a run (private to the run library): each asset's surface extracted
// once, then a frame of posed grains, contact forces and the world's membranes whenever asked.
#pragma once

#include "lsdem/run/VtkSeries.h"
#include "lsdem/simulation/NonAffineMotion.h"
#include "lsdem/simulation/Simulation.h"

#include <map>
#include <vector>
#include <string>

namespace lsdem {

/// The base name of a run's ParaView series: frames.pvd, frames_grains_<k>.vtu, ...
inline const std::string kFramesBaseName = "frames";

class FrameWriter
{
public:
    /// With @a start (each grain's pose at the run's start, by global index; split by space,
    /// on rank 0: the other ranks give an empty list), every frame also carries each grain's
    /// micromechanics: displacement and rotation since then, D²min among the grains near it
    /// then (centres within 1.1 times the sum of their bounding radii), its stress.
    /// Each grain's surface is drawn at @a spacing (0: its asset's node spacing). In a periodic
    /// cell, its size at the start is @a startCellSize (D²min counts the grains' neighbours
    /// across the faces, which the cell's deformation moves since).
    FrameWriter(const std::string& dir, const World& world,
                const std::vector<RigidPose>* start = nullptr, double spacing = 0.0,
                const Vec3& startCellSize = Vec3::Zero());
    VtkSeries& series() { return mSeries; }
    /// Collective when @a sim is split by space (each rank writes its piece; the measures
    /// need the whole simulation).
    void write(const Simulation& sim);

private:
    /// Each grain's measures, by this rank's grain index: worked out for the whole simulation
    /// on rank 0 (here, in one process) and shared.
    std::vector<VtkGrainMeasures> grainMeasures(const Simulation& sim);

    VtkSeries mSeries;
    std::map<const GrainAsset*, TriangleMesh> mSurfaces;
    bool mMeasures = false;
    std::vector<RigidPose> mStart;
    std::vector<Vec3> mStartPositions;
    /// For D²min, found at the first frame (from the whole simulation's bounding radii).
    Vec3 mStartCellSize = Vec3::Zero();
    std::vector<std::vector<PeriodicNeighbour>> mStartNeighbours;
    bool mNeighboursFound = false;
};

} // namespace lsdem
