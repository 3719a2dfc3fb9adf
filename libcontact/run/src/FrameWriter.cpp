#include "FrameWriter.h"

#include "lsdem/ls/Inspection.h"

namespace lsdem {

FrameWriter::FrameWriter(const std::string& dir, const World& world) : mSeries(dir, "frames")
{
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
    std::vector<VtkGrain> grains;
    for (size_t i = 0; i < w.grains.size(); ++i) {
        const Grain& g = w.grains[i];
        grains.push_back({&mSurfaces.at(g.asset.get()), g.body.pose, static_cast<int>(i),
                          g.motion == GrainMotion::Fixed ? Vec3::Zero() : g.body.velocity,
                          g.angularVelocity()});
    }
    std::vector<VtkForcePoint> forces;
    for (const ContactForceRecord& f : sim.contactForces())
        forces.push_back({f.point, f.force, f.grain});
    mSeries.writeFrame(mSeries.framesWritten(), w.time, grains, forces);
}

} // namespace lsdem
