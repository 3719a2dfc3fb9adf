/// @file Packing.h
/// @brief A packing generator: fill a box or a vertical cylinder with a mixture of grain
///        assets, without overlaps, reproducibly from a seed. Grains are inserted at random (random position and
///        orientation, their bounding spheres clear of each other) in a layer above the bed,
///        then deposited under gravity with lsdem's own Simulation until they are at rest;
///        layer after layer until the count is reached or the box is full.
///
///        The deposition is a numerical device: only the geometry is kept. It runs in its own
///        consistent units, with the user's lengths (those of the assets): density 1, gravity 1
///        along −z, global damping 0.3, and an adapted contact stiffness kn* chosen so that the
///        weight of the column a deposition moves (see below: bounded, whatever the container's
///        height) presses a grain into its neighbours by about 1 % of its bounding radius. A layer is at rest when its kinetic energy is below
///        settleTolerance · Σ m_i·g·d_i (d_i: bounding diameter), i.e. the grains' mean speed is
///        below ~sqrt(2·tolerance·g·d), checked after at least twice the time to fall through
///        the layer; layers that later ones will cover settle to 100 times the tolerance.
///
///        The cost of a layer is bounded: only the grains whose centres lie less than
///        kFreeDepthDiameters largest diameters below the new layer's bottom (the top of the
///        bed) move with it; those whose bounding spheres reach a further
///        kSupportDepthDiameters below are held fixed (the bed the moving grains rest on) and
///        the deeper ones are left out of its deposition, below a floor that catches any grain
///        small enough to pass between the fixed ones. So the time grows
///        with the count, not its square.
#pragma once

#include "lsdem/scene/Scene.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lsdem {

struct PackingComponent
{
    std::string name;                          ///< the asset's name in the grains CSV
    std::shared_ptr<const GrainAsset> asset;
    double fraction = 1.0;                     ///< share of the grain count (normalised)
};

/// A vertical circular cylinder (axis along z), filled instead of a box.
struct PackingCylinder
{
    double x = 0.0, y = 0.0;      ///< its axis, length
    double radius = 1.0;
    double zMin = 0.0, zMax = 1.0;  ///< floor and lid
};

/// Largest grain diameters below the new layer's bottom within which grains move with it.
constexpr double kFreeDepthDiameters = 2.5;
/// Largest grain diameters below those, reached by grains held fixed during the deposition.
constexpr double kSupportDepthDiameters = 1.0;

struct PackingOptions
{
    std::vector<PackingComponent> mixture;
    Vec3 boxMin = Vec3::Zero(), boxMax = Vec3::Ones();  ///< the inside of the box, length
    /// Fill this cylinder instead of the box (the box is then not used).
    std::optional<PackingCylinder> cylinder;
    long long count = 0;                       ///< grains wanted
    uint64_t seed = 1;
    double friction = 0.0;                     ///< Coulomb μ during deposition (0: densest)
    double settleTolerance = 1e-5;             ///< kinetic energy / Σ m·g·d at rest
    long long maxStepsPerLayer = 200000;       ///< a layer not at rest by then is taken as it is
    int insertionAttempts = 200;               ///< random tries per grain before a layer is full
};

struct PackingResult
{
    /// The packed grains (assets named as in the mixture, one material "grains"), all free:
    /// write them with writeGrainsCsv(scene, 0, scene.grains.size(), path).
    Scene scene;
    bool complete = false;       ///< all of options.count fitted
    double solidFraction = 0.0;  ///< Σ grain volumes / the container's volume
    double maxOverlap = 0.0;     ///< deepest grain–grain overlap / smaller bounding radius
    int layers = 0;
    long long steps = 0;
    int unsettledLayers = 0;     ///< layers that hit maxStepsPerLayer
    long long largestLayerGrains = 0;  ///< most grains (moving and fixed) in one deposition
    double seconds = 0.0;
};

/// Fill the box or cylinder of @a options. @a progress (may be empty) is told after each layer.
/// @throw Error for bad options (no assets, a fraction < 0, an empty box or cylinder, a count
///        < 1, a grain larger than the container).
PackingResult generatePacking(const PackingOptions& options,
                              const std::function<void(const PackingResult&)>& progress = {});

} // namespace lsdem
