// The settled heaps bench_scale times (see bench_scale.cpp's opening comment): ten sand-like
// ellipsoid assets, a tile of 250 grains settled once per process, and tiles side by side for
// 1,000 to 100,000 grains, stepped past a prefix before anything is timed.
#pragma once

#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/Simulation.h"

#include <memory>
#include <string>
#include <vector>

namespace lsdem::scalebench {

constexpr int kAssetCount = 10;

/// The ten sand-like assets, baked once per process (a second each).
const std::vector<std::shared_ptr<const GrainAsset>>& sandAssets();
/// Pairs (grain–grain and grain–wall) with at least one node in contact: exactly those with
/// a shear history after the last step (friction is on).
double contactsNow(const World& w);
/// A scene with the assets, the sand and wall materials and their contacts, gravity and
/// damping, and no grains or walls yet.
Scene sandScene();

/// A grain count's settled state, with what building it cost in memory.
struct Settled
{
    int grains = 0;
    std::unique_ptr<Simulation> sim;
    double peakMiB = 0.0;          ///< VmHWM over building and settling
    double heldBytesPerGrain = 0.0;  ///< resident growth over the build, per grain
};

/// The state after the settling prefix, made once per grain count (the last one is kept).
const Settled& settled(int grains);

} // namespace lsdem::scalebench
