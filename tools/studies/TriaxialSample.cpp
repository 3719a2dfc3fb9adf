#include "studies/TriaxialSample.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/RandomRotation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <random>
#include <set>

namespace lsdem {

std::vector<std::string> triaxialAssetNames(const std::vector<std::string>& meshFiles)
{
    auto stemOf = [](const std::string& file) {
        return std::filesystem::path(file).stem().string();
    };
    std::set<std::string> stems, taken;
    for (const std::string& file : meshFiles) stems.insert(stemOf(file));
    std::vector<std::string> names;
    for (const std::string& file : meshFiles) {
        const std::string stem = stemOf(file);
        std::string name = stem;
        // A suffix no file has as its own name, so every file keeps its stem if it can.
        for (int k = 2; taken.count(name) > 0 || (name != stem && stems.count(name) > 0); ++k)
            name = stem + "_" + std::to_string(k);
        taken.insert(name);
        names.push_back(name);
    }
    return names;
}

TriaxialAssets bakeTriaxialAssets(const std::vector<std::string>& meshFiles, double vdp,
                                  double sdp)
{
    const Stopwatch clock;
    TriaxialAssets a;
    a.vdp = vdp;
    a.sdp = sdp;
    a.assets.resize(meshFiles.size());
    BakeOptions bake;
    bake.voxelSize = vdp;
    bake.nodePlacement = NodePlacement::Spacing;
    bake.nodeSpacing = sdp;
    bake.optionsText = "lsdem-study triaxial: voxel " + numberText(vdp) + ", node spacing " +
                       numberText(sdp);
    // One file per task; each bake is itself threaded, TBB shares the cores among them.
    tbb::parallel_for(size_t(0), meshFiles.size(), [&](size_t i) {
        std::vector<std::string> warnings;  // repairs and spacing notes: not the study's concern
        a.assets[i] = std::make_shared<const GrainAsset>(bakeMeshFile(meshFiles[i], bake, warnings));
    });
    a.names = triaxialAssetNames(meshFiles);
    double nodes = 0.0, area = 0.0, diameter = 0.0;
    for (size_t i = 0; i < meshFiles.size(); ++i) {
        const GrainAsset& g = *a.assets[i];
        nodes += double(g.nodes.size());
        area += g.nodes.totalArea();
        diameter += std::cbrt(6.0 * g.mass.volume / kPi);
        a.largestBoundingRadius = std::max(a.largestBoundingRadius, g.boundingRadius);
    }
    const double n = double(meshFiles.size());
    a.meanNodes = nodes / n;
    a.meanNodeArea = area / nodes;
    a.meanDiameter = diameter / n;
    a.bakeSeconds = clock.seconds();
    return a;
}

std::shared_ptr<const TriaxialAssets> sharedTriaxialAssets(const std::vector<std::string>& meshFiles,
                                                           double vdp, double sdp)
{
    static std::mutex mutex;
    static std::map<std::pair<double, double>, std::shared_ptr<const TriaxialAssets>> baked;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& slot = baked[{vdp, sdp}];
    if (!slot) slot = std::make_shared<const TriaxialAssets>(bakeTriaxialAssets(meshFiles, vdp, sdp));
    return slot;
}

double triaxialCloudSpacing(const TriaxialAssets& assets)
{
    return 2.2 * assets.largestBoundingRadius;
}

TriaxialCloud makeTriaxialCloud(long long count, int meshCount, double spacing,
                                std::uint64_t seed, double heightRatio)
{
    // Sites per side: a cube (or a prism heightRatio times as tall) when the count is one, else
    // the base it would have and as many layers as it takes.
    const long long side = std::max(
        2LL, static_cast<long long>(std::floor(std::cbrt(double(count) / heightRatio) + 1e-9)));
    const long long layers = (count + side * side - 1) / (side * side);
    std::mt19937_64 rng(seed);
    TriaxialCloud c;
    for (long long k = 0; k < count; ++k) {
        const long long i = k % side, j = (k / side) % side, l = k / (side * side);
        c.asset.push_back(static_cast<int>(rng() % static_cast<std::uint64_t>(meshCount)));
        RigidPose pose;
        pose.position = spacing * Vec3(double(i) + 0.5, double(j) + 0.5, double(l) + 0.5);
        pose.orientation = randomRotation(rng);
        c.pose.push_back(pose);
    }
    c.boxMin = Vec3::Zero();
    c.boxMax = spacing * Vec3(double(side), double(side), double(layers));
    return c;
}

Scene triaxialScene(const TriaxialOptions& o, const TriaxialAssets& assets,
                    const TriaxialCloud& cloud, Formulation f, double kn)
{
    Scene s;
    for (size_t i = 0; i < assets.assets.size(); ++i) {
        AssetSpec a;
        a.name = assets.names[i];
        a.loaded = assets.assets[i];
        s.assets.push_back(a);
    }
    s.materials.push_back({"grain", o.density});
    s.materials.push_back({"wall", 0.0});
    auto law = [&](int other, double friction) {
        ContactSpec c;
        c.materialA = 0;
        c.materialB = other;
        c.model.formulation = f;
        c.model.normalStiffness = kn;
        c.model.shearStiffness = o.shearRatio * kn;
        c.model.friction = friction;
        s.contacts.push_back(c);
    };
    law(0, o.friction);
    law(1, o.wallFriction);
    for (size_t k = 0; k < cloud.asset.size(); ++k) {
        GrainSpec g;
        g.asset = cloud.asset[k];
        g.material = 0;
        g.pose = cloud.pose[k];
        s.grains.push_back(g);
    }
    s.globalDamping = o.globalDamping;
    if (o.periodic) {  // the lattice's box repeats: no walls
        s.periodicOrigin = cloud.boxMin;
        s.periodicCell = cloud.boxMax - cloud.boxMin;
        return s;
    }
    const char* names[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};
    for (int w = 0; w < 6; ++w) {
        const int axis = w / 2;
        const bool low = w % 2 == 0;
        BoundarySpec b;
        b.name = names[w];
        b.material = 1;
        b.point = low ? cloud.boxMin : cloud.boxMax;
        b.normal = (low ? 1.0 : -1.0) * Vec3::Unit(axis);
        s.boundaries.push_back(b);
    }
    return s;
}

TriaxialWalls triaxialWalls()
{
    return TriaxialWalls{{0, 1, 2, 3, 4, 5}};
}

} // namespace lsdem
