// The packing generator: random insertion layer by layer, each layer deposited under gravity
// with the Simulation until it is at rest, only the top of the bed moving with it (see
// Packing.h for the numerical set-up).
#include "lsdem/scene/Packing.h"

#include "PackingContainer.h"

#include "lsdem/core/Constants.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/Stopwatch.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/RandomRotation.h"
#include "lsdem/simulation/GrainOverlaps.h"
#include "lsdem/simulation/Simulation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>

namespace lsdem {

namespace {

constexpr double kDensity = 1.0;      // the deposition's own units (Packing.h)
constexpr double kGravity = 1.0;
constexpr double kDamping = 0.3;
constexpr double kRestOverlap = 0.01;  // static overlap / bounding radius under the column
constexpr double kLayerDiameters = 3.0;  // insertion layer height, in largest grain diameters

/// Grains per component: the floor of fraction·count, plus one for the largest remainders
/// (the earlier component on a tie), so they add up to count.
std::vector<long long> componentCounts(const PackingOptions& o)
{
    // Shares of the largest fraction: they add up to at most the number of components, where
    // finite fractions such as 1e308 1e308 added up to inf (and floor(NaN) became a count).
    double largest = 0.0;
    for (const PackingComponent& c : o.mixture) largest = std::max(largest, c.fraction);
    double total = 0.0;
    for (const PackingComponent& c : o.mixture) total += c.fraction / largest;
    std::vector<long long> counts;
    std::vector<std::pair<double, size_t>> remainders;
    long long sum = 0;
    for (size_t k = 0; k < o.mixture.size(); ++k) {
        const double exact =
            static_cast<double>(o.count) * (o.mixture[k].fraction / largest) / total;
        counts.push_back(static_cast<long long>(std::floor(exact)));
        sum += counts.back();
        remainders.emplace_back(-(exact - std::floor(exact)), k);
    }
    std::stable_sort(remainders.begin(), remainders.end());
    for (size_t k = 0; sum < o.count; ++k, ++sum) ++counts[remainders[k % remainders.size()].second];
    return counts;
}

/// The components in insertion order: shuffled (Fisher–Yates on lsdem's own uniform
/// numbers, so a seed gives the same order with any standard library).
std::vector<int> insertionOrder(const std::vector<long long>& counts, std::mt19937_64& rng)
{
    std::vector<int> order;
    for (size_t k = 0; k < counts.size(); ++k) order.insert(order.end(), size_t(counts[k]), int(k));
    for (size_t i = order.size(); i > 1; --i) {
        const size_t j = std::min(i - 1, static_cast<size_t>(uniform01(rng) * double(i)));
        std::swap(order[i - 1], order[j]);
    }
    return order;
}

/// The scene the deposition runs (without grains): the mixture's assets, one material, the
/// adapted law with @a knStar, a floor and four side walls or a cylinder, gravity and damping.
Scene depositionScene(const PackingOptions& o, double knStar)
{
    Scene s;
    for (const PackingComponent& c : o.mixture) {
        AssetSpec a;
        a.name = c.name;
        a.loaded = c.asset;
        s.assets.push_back(a);
    }
    s.materials.push_back({"grains", kDensity});
    ContactSpec law;
    law.model.formulation = Formulation::Adapted;
    law.model.normalStiffness = knStar;
    if (o.friction > 0.0) {
        law.model.friction = o.friction;
        law.model.shearStiffness = 0.5 * knStar;
    }
    s.contacts.push_back(law);
    auto wall = [&](const char* name, const Vec3& point, const Vec3& normal) {
        BoundarySpec b;
        b.name = name;
        b.point = point;
        b.normal = normal;
        s.boundaries.push_back(b);
    };
    wall("floor", containerMin(o), Vec3::UnitZ());
    if (o.cylinder) {
        BoundarySpec side;
        side.name = "side";
        side.shape = BoundaryShape::Cylinder;
        side.center = Vec3(o.cylinder->x, o.cylinder->y, o.cylinder->zMin);
        side.axis = Vec3::UnitZ();
        side.radius = o.cylinder->radius;
        s.boundaries.push_back(side);
    } else {
        wall("x0", o.boxMin, Vec3::UnitX());
        wall("x1", o.boxMax, -Vec3::UnitX());
        wall("y0", o.boxMin, Vec3::UnitY());
        wall("y1", o.boxMax, -Vec3::UnitY());
    }
    s.gravity = Vec3(0, 0, -kGravity);
    s.globalDamping = kDamping;
    return s;
}

/// Random sequential insertion in the layer [zLow, zHigh] of the container: each grain of
/// @a order from @a next gets up to @a attempts random centres (its bounding sphere inside the
/// layer and the container, clear of every other bounding sphere) and a random orientation.
/// Stops at the first grain that finds no room. @return how many were placed.
size_t insertLayer(const PackingOptions& o, const std::vector<int>& order, size_t next,
                   double zLow, double zHigh, std::mt19937_64& rng, Scene& scene)
{
    const Vec3 boxMin = containerMin(o), boxMax = containerMax(o);
    // Only grains reaching into the layer can be in the way.
    std::vector<std::pair<Vec3, double>> near;
    for (const GrainSpec& g : scene.grains) {
        const double r = o.mixture[size_t(g.asset)].asset->boundingRadius;
        if (g.pose.position.z() + r > zLow) near.emplace_back(g.pose.position, r);
    }
    size_t placed = 0;
    for (size_t i = next; i < order.size(); ++i) {
        const int component = order[i];
        const double r = o.mixture[size_t(component)].asset->boundingRadius;
        const Vec3 lo(boxMin.x() + r, boxMin.y() + r, zLow + r);
        const Vec3 hi(boxMax.x() - r, boxMax.y() - r, zHigh - r);
        if (!((hi - lo).minCoeff() >= 0.0)) break;
        bool found = false;
        Vec3 c;
        for (int attempt = 0; attempt < o.insertionAttempts && !found; ++attempt) {
            for (int d = 0; d < 3; ++d) c[d] = lo[d] + (hi[d] - lo[d]) * uniform01(rng);
            // In a cylinder: a centre uniform in the disc of radius R - r (by rejection from
            // its square: the draws, and so the packing, still follow from the seed alone).
            if (o.cylinder) {
                const double reach = o.cylinder->radius - r;
                while (std::hypot(c.x() - o.cylinder->x, c.y() - o.cylinder->y) > reach)
                    for (int d = 0; d < 2; ++d) c[d] = lo[d] + (hi[d] - lo[d]) * uniform01(rng);
            }
            found = std::none_of(near.begin(), near.end(), [&](const auto& other) {
                const double reach = r + other.second;
                return (c - other.first).squaredNorm() < reach * reach;
            });
        }
        if (!found) break;
        GrainSpec g;
        g.asset = component;
        g.material = 0;
        g.pose.position = c;
        g.pose.orientation = randomRotation(rng);
        scene.grains.push_back(g);
        near.emplace_back(c, r);
        ++placed;
    }
    return placed;
}

/// The deposition's scales from the mixture (by count): the contact stiffness, the step, a
/// layer's height and the time a grain takes to fall through it.
struct DepositionScales
{
    double largest = 0.0;  ///< the largest bounding diameter
    double knStar = 0.0;
    double dt = 0.0;
    double layerHeight = 0.0;
    double fallTime = 0.0;
};

DepositionScales depositionScales(const PackingOptions& o, const std::vector<int>& order)
{
    double meanRadius = 0.0, meanVolume = 0.0, largest = 0.0, lightest = 1e300;
    for (int k : order) {
        const GrainAsset& a = *o.mixture[size_t(k)].asset;
        meanRadius += a.boundingRadius / double(order.size());
        meanVolume += a.mass.volume / double(order.size());
        largest = std::max(largest, 2.0 * a.boundingRadius);
        lightest = std::min(lightest, kDensity * a.mass.volume);
    }
    DepositionScales d;
    d.largest = largest;
    // kn* so that the weight of the column a deposition moves (height / mean diameter grains)
    // presses a grain by kRestOverlap of its radius: n·m·g = π·kn*·R·δ² (a sphere on a plane),
    // δ = ε·R. That column is at most the new layer and the free depth above the fixed band,
    // whatever the container's height: grains further down are held or left out.
    const double height =
        std::min(containerMax(o).z() - containerMin(o).z(),
                 (kLayerDiameters + kFreeDepthDiameters + kSupportDepthDiameters) * largest);
    const double layers = std::max(1.0, height / (2.0 * meanRadius));
    d.knStar = layers * kDensity * meanVolume * kGravity /
               (kPi * kRestOverlap * kRestOverlap * std::pow(meanRadius, 3));
    // The step: a fifth of sqrt(m/k) for the lightest grain held by four contacts, each
    // pressed by three times the rest overlap of the largest grain (a landing): k = 2π·kn*·R·δ.
    // A step the stability check refuses is halved and the layer deposited again.
    const double rMax = 0.5 * largest;
    const double contactStiffness = 2.0 * kPi * d.knStar * rMax * 3.0 * kRestOverlap * rMax;
    d.dt = 0.2 * std::sqrt(lightest / (4.0 * contactStiffness));
    d.layerHeight = kLayerDiameters * largest;
    d.fallTime = std::sqrt(2.0 * d.layerHeight / kGravity);
    return d;
}

/// The grains of one deposition: those whose centres lie above the free depth below the new
/// layer's bottom @a bedTop move (the new layer, from @a before on, among them); those
/// reaching into the support band below are held fixed; the deeper ones are buried and left
/// out. @a moving gets the indices into @a packed.grains of the free grains, in order.
Scene depositionLayer(const PackingOptions& o, const Scene& base, const Scene& packed,
                      size_t before, double bedTop, double largest, double floorZ,
                      std::vector<size_t>& moving)
{
    const double freeBottom = bedTop - kFreeDepthDiameters * largest;
    const double supportBottom = freeBottom - kSupportDepthDiameters * largest;
    Scene layer = base;
    moving.clear();
    for (size_t i = 0; i < packed.grains.size(); ++i) {
        const GrainSpec& g = packed.grains[i];
        const double z = g.pose.position.z();
        const double r = o.mixture[size_t(g.asset)].asset->boundingRadius;
        if (i >= before || z > freeBottom) {
            moving.push_back(i);
            layer.grains.push_back(g);
        } else if (z + r > supportBottom) {
            layer.grains.push_back(g);
            layer.grains.back().motion = GrainMotion::Fixed;
        }
    }
    // A grain small enough to pass between the fixed ones (a wide size range) lands on a
    // floor at the bottom of the support band, not inside the grains left out below it.
    if (supportBottom > floorZ) {
        BoundarySpec bed;
        bed.name = "buried";
        bed.point = Vec3(0, 0, supportBottom);
        bed.normal = Vec3::UnitZ();
        layer.boundaries.push_back(bed);
    }
    return layer;
}

/// Deposit @a layer from rest until its kinetic energy is below @a tolerance of its grains'
/// rest energy (or the step limit); a step the stability check refuses is halved in @a dt and
/// the layer deposited again. The simulation at its end; @a steps and @a atRest say how it went.
std::unique_ptr<Simulation> depositFromRest(const PackingOptions& o, const Scene& layer,
                                            double fallTime, double tolerance, double& dt,
                                            long long& steps, bool& atRest)
{
    std::vector<std::string> warnings;
    for (int attempt = 0;; ++attempt) {
        try {
            auto sim = std::make_unique<Simulation>(buildWorld(layer, warnings), dt);
            double restEnergy = 0.0;
            for (const Grain& g : sim->world().grains)
                if (g.isFree()) restEnergy += g.body.mass * kGravity * 2.0 * g.asset->boundingRadius;
            steps = 0;
            atRest = false;
            while (!atRest && steps < o.maxStepsPerLayer) {
                for (int k = 0; k < 100; ++k) sim->step();
                steps += 100;
                atRest = sim->world().time > 2.0 * fallTime &&
                         sim->energies().kinetic < tolerance * restEnergy;
            }
            return sim;
        } catch (const Error&) {
            if (attempt >= 5) throw;  // not a matter of the step
            dt *= 0.5;
        }
    }
}

/// The largest overlap of any two grains of @a scene, relative to the smaller's bounding radius.
double largestRelativeOverlap(const Scene& scene)
{
    if (scene.grains.empty()) return 0.0;
    std::vector<std::string> warnings;
    const World w = buildWorld(scene, warnings);
    double largest = 0.0;
    for (const GrainOverlap& v : findGrainOverlaps(w))
        largest = std::max(largest, v.depth / std::min(w.grains[size_t(v.first)].asset->boundingRadius,
                                                       w.grains[size_t(v.second)].asset->boundingRadius));
    return largest;
}

} // namespace

PackingResult generatePacking(const PackingOptions& o,
                              const std::function<void(const PackingResult&)>& progress)
{
    checkPackingOptions(o);
    const Stopwatch clock;
    std::mt19937_64 rng(o.seed);
    const std::vector<int> order = insertionOrder(componentCounts(o), rng);
    DepositionScales scales = depositionScales(o, order);

    PackingResult result;
    const Scene base = depositionScene(o, scales.knStar);
    result.scene = base;
    const double floorZ = containerMin(o).z(), lidZ = containerMax(o).z();
    size_t next = 0;
    double bedTop = floorZ;
    while (next < order.size()) {
        const double zHigh = std::min(lidZ, bedTop + scales.layerHeight);
        const size_t before = result.scene.grains.size();
        const size_t placed = insertLayer(o, order, next, bedTop, zHigh, rng, result.scene);
        if (placed == 0) break;  // the container is full
        next += placed;
        ++result.layers;
        std::vector<size_t> moving;
        const Scene layer = depositionLayer(o, base, result.scene, before, bedTop, scales.largest,
                                            floorZ, moving);
        result.largestLayerGrains =
            std::max(result.largestLayerGrains, static_cast<long long>(layer.grains.size()));
        // A layer that more will cover only needs to be roughly at rest: 100 times the tolerance.
        const double tolerance =
            next == order.size() ? o.settleTolerance : 100.0 * o.settleTolerance;
        long long steps = 0;
        bool atRest = false;
        const std::unique_ptr<Simulation> sim =
            depositFromRest(o, layer, scales.fallTime, tolerance, scales.dt, steps, atRest);
        result.steps += steps;
        result.unsettledLayers += atRest ? 0 : 1;
        // The layer's free grains are those of `moving`, in the same order.
        for (size_t i = 0, k = 0; i < layer.grains.size(); ++i) {
            if (layer.grains[i].motion == GrainMotion::Fixed) continue;
            result.scene.grains[moving[k++]].pose = sim->world().grains[i].body.pose;
        }
        bedTop = floorZ;
        double volume = 0.0;
        for (const GrainSpec& g : result.scene.grains) {
            const GrainAsset& a = *o.mixture[size_t(g.asset)].asset;
            bedTop = std::max(bedTop, g.pose.position.z() + a.boundingRadius);
            volume += a.mass.volume;
        }
        result.solidFraction = volume / containerVolume(o);
        result.seconds = clock.seconds();
        if (progress) progress(result);
    }
    result.complete = next == order.size();
    result.maxOverlap = largestRelativeOverlap(result.scene);
    result.seconds = clock.seconds();
    return result;
}

} // namespace lsdem
