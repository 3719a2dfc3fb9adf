// The ParaView output of a run (private to the run library): each asset's surface extracted
// once, then a frame of posed grains and contact forces whenever asked.
#pragma once

#include "lsdem/run/VtkSeries.h"
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
    /// With @a start (each grain's pose at the run's start), every frame also carries each
    /// grain's micromechanics: displacement and rotation since then, D²min among the grains
    /// near it then (centres within 1.1 times the sum of their bounding radii), its stress.
    FrameWriter(const std::string& dir, const World& world,
                const std::vector<RigidPose>* start = nullptr);
    VtkSeries& series() { return mSeries; }
    void write(const Simulation& sim);

private:
    VtkSeries mSeries;
    std::map<const GrainAsset*, TriangleMesh> mSurfaces;
    std::vector<RigidPose> mStart;                   ///< empty: no measures
    std::vector<Vec3> mStartPositions;
    std::vector<std::vector<int>> mStartNeighbours;  ///< for D²min
};

} // namespace lsdem
