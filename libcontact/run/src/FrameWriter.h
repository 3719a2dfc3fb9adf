// The ParaView output of a run (private to the run library): each asset's surface extracted
// once, then a frame of posed grains and contact forces whenever asked.
#pragma once

#include "lsdem/run/VtkSeries.h"
#include "lsdem/simulation/Simulation.h"

#include <map>
#include <string>

namespace lsdem {

/// The base name of a run's ParaView series: frames.pvd, frames_grains_<k>.vtu, ...
inline const std::string kFramesBaseName = "frames";

class FrameWriter
{
public:
    FrameWriter(const std::string& dir, const World& world);
    VtkSeries& series() { return mSeries; }
    void write(const Simulation& sim);

private:
    VtkSeries mSeries;
    std::map<const GrainAsset*, TriangleMesh> mSurfaces;
};

} // namespace lsdem
