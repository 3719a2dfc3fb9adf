#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneValidation.h"

#include "SceneChecks.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"
#include "lsdem/core/NumberText.h"
#include "lsdem/core/RunInParallel.h"
#include "lsdem/simulation/GrainOverlaps.h"
#include "lsdem/scene/MembraneKeys.h"

#include <algorithm>
#include <map>
#include <limits>
#include <sstream>

namespace lsdem {

namespace {

/// The world's own copy of an asset holds no node normals (SurfaceNodes::normals says why).
/// An asset handed in already loaded is shared with its owner and kept whole.
std::shared_ptr<const GrainAsset> withoutNormals(GrainAsset asset)
{
    asset.nodes.dropNormals();
    return std::make_shared<const GrainAsset>(std::move(asset));
}

std::shared_ptr<const GrainAsset> loadOrBake(const AssetSpec& spec,
                                             std::vector<std::string>& warnings)
{
    if (spec.loaded) return spec.loaded;
    try {
        if (!spec.file.empty()) return loadAsset(spec.file, NodeNormals::Skip);
        if (!spec.meshFile.empty())
            return withoutNormals(bakeMeshFile(spec.meshFile, spec.bake, warnings));
        if (spec.shape) return withoutNormals(bakeAnalytic(*spec.shape, spec.bake, warnings));
    } catch (const Error& e) {
        throw Error(spec.where, "asset '" + spec.name + "': " + e.what());
    }
    throw Error(spec.where, "asset '" + spec.name + "' has no source",
                "give file, mesh or shape");
}

/// Every asset of @a specs, loaded or baked in parallel (a scene of thousands of distinct
/// scanned grains loads on every core it may use), with the outcome of one by one.
std::vector<std::shared_ptr<const GrainAsset>> loadOrBakeAll(const std::vector<AssetSpec>& specs,
                                                             std::vector<std::string>& warnings)
{
    std::vector<std::shared_ptr<const GrainAsset>> assets(specs.size());
    std::vector<std::vector<std::string>> assetWarnings(specs.size());
    const FirstFailure failed = runInParallel(
        specs.size(), [&](size_t k) { assets[k] = loadOrBake(specs[k], assetWarnings[k]); });
    // Through the failed asset's own: what one by one would have gathered before it threw.
    for (size_t k = 0; k < std::min(failed.index + 1, specs.size()); ++k)
        warnings.insert(warnings.end(), assetWarnings[k].begin(), assetWarnings[k].end());
    failed.rethrowIfAny();
    return assets;
}

/// Where a contact integrates node patches (PatchQuadrature.h), its grains' assets (and a
/// level-set boundary's) need their node shapes: every asset gets them then, in a copy (an
/// asset handed in is its owner's), shared by its grains. Refused against a boundary shape
/// that has no patch quadrature yet.
void addNodeShapesWherePatchesAre(const Scene& scene, World& w)
{
    bool any = false;
    for (const ContactSpec& c : scene.contacts) any |= c.model.quadrature == NodeQuadrature::Patch;
    if (!any) return;
    for (size_t k = 0; k < scene.boundaries.size(); ++k) {
        const Boundary& b = w.boundaries[k];
        if (integratesPatches(b.shape)) continue;
        for (const ContactSpec& c : scene.contacts)
            if (c.model.quadrature == NodeQuadrature::Patch &&
                (c.materialA == b.material || c.materialB == b.material))
                throw Error(scene.boundaries[k].where,
                            "boundary '" + b.name + "' has no patch quadrature (its shape is not "
                            "a plane, a sphere or a level set)",
                            "give the contact between materials '" +
                                scene.materials[c.materialA].name + "' and '" +
                                scene.materials[c.materialB].name + "' quadrature = \"node\"");
    }
    std::map<const GrainAsset*, std::shared_ptr<const GrainAsset>> shaped;
    auto withShapes = [&](const std::shared_ptr<const GrainAsset>& a) {
        std::shared_ptr<const GrainAsset>& s = shaped[a.get()];
        if (!s) s = std::make_shared<const GrainAsset>(withNodeShapes(*a));
        return s;
    };
    for (std::shared_ptr<const GrainAsset>& a : w.assets) a = withShapes(a);
    for (Grain& g : w.grains) g.asset = withShapes(g.asset);
    for (Boundary& b : w.boundaries)
        if (b.asset) b.asset = withShapes(b.asset);
}

Grain makeGrain(const GrainSpec& spec, const Scene& scene,
                const std::shared_ptr<const GrainAsset>& asset)
{
    Grain g;
    g.name = spec.name;
    g.asset = asset;
    g.material = spec.material;
    g.motion = spec.motion;
    const double density = scene.materials[spec.material].density;
    const double volume = asset->mass.volume;
    const double mass = spec.mass > 0.0 ? spec.mass : density * volume;
    if (g.isFree() && !(mass > 0.0))
        throw Error(spec.where, "free grain '" + spec.name + "' has no mass",
                    "give its material a density > 0 or the grain a mass");
    RigidBody& b = g.body;
    b.pose = spec.pose;
    b.velocity = spec.velocity;
    b.mass = mass > 0.0 ? mass : 1.0;  // immovable grains never use it
    // The asset's inertia is for unit density: scale by the grain's mass over its volume.
    b.principalInertia = asset->mass.inertia.diagonal() * (b.mass / volume);
    if (g.motion == GrainMotion::Prescribed) g.prescribedAngularVelocity = spec.angularVelocity;
    if (g.isFree()) b.setAngularVelocity(spec.angularVelocity);
    if (g.motion != GrainMotion::Free && g.motion != GrainMotion::Prescribed)
        b.velocity = Vec3::Zero();
    return g;
}

/// Grains read from files may not overlap (beyond their file's max_overlap) with any other:
/// measured with the level sets (GrainOverlaps.h); the deepest offending pair is reported.
void checkGrainFileOverlaps(const Scene& scene, const World& w)
{
    if (scene.grainFiles.empty()) return;
    std::vector<const GrainFileSpec*> fileOf(w.grains.size(), nullptr);
    for (const GrainFileSpec& f : scene.grainFiles)
        for (size_t i = f.first; i < f.first + f.count; ++i) fileOf[i] = &f;
    const GrainOverlap* worst = nullptr;
    double worstTolerance = 0.0;
    long long offending = 0;
    const std::vector<GrainOverlap> overlaps = findGrainOverlaps(w);
    for (const GrainOverlap& o : overlaps) {
        const GrainFileSpec* fa = fileOf[size_t(o.first)];
        const GrainFileSpec* fb = fileOf[size_t(o.second)];
        if (!fa && !fb) continue;
        const double fallback = 0.05 * std::min(w.grains[size_t(o.first)].asset->boundingRadius,
                                                w.grains[size_t(o.second)].asset->boundingRadius);
        double tolerance = std::numeric_limits<double>::infinity();
        for (const GrainFileSpec* f : {fa, fb})
            if (f) tolerance = std::min(tolerance, f->maxOverlap >= 0.0 ? f->maxOverlap : fallback);
        if (!(o.depth > tolerance)) continue;
        ++offending;
        if (!worst || o.depth - tolerance > worst->depth - worstTolerance)
            worst = &o, worstTolerance = tolerance;
    }
    if (!worst) return;
    const GrainSpec& a = scene.grains[size_t(worst->first)];
    const GrainSpec& b = scene.grains[size_t(worst->second)];
    const GrainFileSpec& file = *(fileOf[size_t(worst->first)] ? fileOf[size_t(worst->first)]
                                                               : fileOf[size_t(worst->second)]);
    std::ostringstream problem;
    problem << "grains '" << w.grains[size_t(worst->first)].name << "' (" << a.where << ") and '"
            << w.grains[size_t(worst->second)].name << "' (" << b.where << ") overlap by "
            << worst->depth << " (the deepest node of one inside the other's level set), more than "
            << worstTolerance;
    if (offending > 1) problem << "; " << offending - 1 << " other pair(s) overlap too much";
    throw Error(fileOf[size_t(worst->first)] ? a.where : b.where, problem.str(),
                "move them apart, or allow it with max_overlap in the [[grain_files]] table at " +
                    file.where + " (default: 5 % of the smaller grain's bounding radius)");
}

} // namespace

Boundary makeBoundary(const BoundarySpec& spec, std::shared_ptr<const GrainAsset> asset)
{
    Boundary b;
    b.name = spec.name;
    b.shape = spec.shape;
    b.material = spec.material;
    b.velocity = spec.velocity;
    b.servo = spec.servo;
    b.plane.point = spec.point;
    b.plane.normal = spec.normal.normalized();
    b.plane.axisU = spec.axisU;
    if (spec.extentU > 0.0) b.plane.halfU = 0.5 * spec.extentU;
    if (spec.extentV > 0.0) b.plane.halfV = 0.5 * spec.extentV;
    if (spec.thickness > 0.0) b.plane.thickness = spec.thickness;
    b.thickness = spec.thickness;
    b.center = spec.center;
    b.radius = spec.radius;
    b.axis = spec.axis.normalized();
    b.asset = std::move(asset);
    b.pose = spec.pose;
    return b;
}

namespace {

/// The scene's periodic cell, if any: checked against the grains (a pair must not reach two
/// images of each other) and every grain moved into it by whole periods (where it starts).
void placeInPeriodicCell(const Scene& scene, World& w)
{
    w.periodic.size = scene.periodicCell;
    w.periodic.origin = scene.periodicOrigin;
    w.periodic.strainRate = scene.periodicStrainRate;
    w.periodic.targetStress = scene.periodicStress;
    w.periodic.maxStrainRate = scene.periodicMaxStrainRate;
    for (int a = 0; a < 3; ++a) {
        const std::string axis(1, "xyz"[a]);
        const auto refuse = [&](const std::string& key, const std::string& what,
                                const std::string& fix) {
            throw Error(scene.path, "[simulation] " + key + ": " + what, fix);
        };
        const bool controlled = scene.periodicStress[a] > 0.0;
        if ((scene.periodicStrainRate[a] != 0.0 || controlled) && !w.periodic.periodic(a))
            refuse(controlled ? "periodic_stress" : "periodic_strain_rate",
                   "the cell is not periodic along " + axis + ", so it cannot deform along it",
                   "give periodic_cell a period along " + axis + ", or 0 there");
        if (controlled && scene.periodicStrainRate[a] != 0.0)
            refuse("periodic_strain_rate", "along " + axis + " the stress is controlled",
                   "give " + axis + " a strain rate of 0 (periodic_stress drives it)");
        if (controlled && !(scene.periodicMaxStrainRate[a] > 0.0))
            refuse("periodic_max_strain_rate",
                   "along " + axis + " the stress is controlled, but the servo may not strain it",
                   "give periodic_max_strain_rate > 0 along " + axis +
                       " (e.g. 10 × the strain rates you want quasi-static)");
        if (controlled && !(scene.periodicCell.minCoeff() > 0.0))
            refuse("periodic_stress", "stress control needs the cell's volume",
                   "make the cell periodic along all three axes, or drive " + axis +
                       " by periodic_strain_rate");
        if (!controlled && scene.periodicMaxStrainRate[a] > 0.0)
            refuse("periodic_max_strain_rate", "along " + axis + " no stress is controlled",
                   "give periodic_stress along " + axis + ", or leave this 0");
    }
    if (!w.periodic.active()) return;
    double largest = 0.0;
    for (const Grain& g : w.grains) largest = std::max(largest, g.asset->boundingRadius);
    w.periodic.leastSize = PeriodicCell::kLeastSizeOverRadius * largest;
    const int a = w.periodic.axisBelowLeastSize(w.periodic.size);
    if (a >= 0)
        throw Error(scene.path,
                    std::string("[simulation] periodic_cell: the period along ") + "xyz"[a] +
                        " (" + numberText(w.periodic.size[a]) + ") is " +
                        w.periodic.leastSizeProblem(),
                    "make the cell at least " + numberText(w.periodic.leastSize) + " along " +
                        "xyz"[a]);
    for (Grain& g : w.grains) g.body.pose.position += w.periodic.shiftInto(g.body.pose.position);
}

} // namespace

World buildWorld(const Scene& scene, std::vector<std::string>& warnings)
{
    // A scene built in code has not been through the file reader's checks: a pair of materials
    // without a law would get the zero model, and its grains would pass through each other;
    // two grains of one name would be two rows of one name in grains.csv.
    validateScene(scene);
    World w;
    w.assets = loadOrBakeAll(scene.assets, warnings);

    w.materialCount = static_cast<int>(scene.materials.size());
    for (const MaterialSpec& m : scene.materials) w.materialNames.push_back(m.name);
    w.models.assign(static_cast<size_t>(w.materialCount) * w.materialCount, ContactModel{});
    for (const ContactSpec& c : scene.contacts) {
        const ContactModel& m = c.model;
        w.models[static_cast<size_t>(c.materialA) * w.materialCount + c.materialB] = m;
        w.models[static_cast<size_t>(c.materialB) * w.materialCount + c.materialA] = m;
    }

    for (const GrainSpec& spec : scene.grains)
        w.grains.push_back(makeGrain(spec, scene, w.assets.at(spec.asset)));
    for (size_t i = 0; i < w.grains.size(); ++i)
        if (w.grains[i].name.empty()) w.grains[i].name = defaultGrainName(i);
    checkGrainFileOverlaps(scene, w);
    for (const BoundarySpec& spec : scene.boundaries)
        w.boundaries.push_back(
            makeBoundary(spec, spec.asset >= 0 ? w.assets.at(spec.asset) : nullptr));

    for (const MembraneSpec& spec : scene.membranes)
        w.membranes.push_back(makeMembrane(spec, scene.boundaries));

    addNodeShapesWherePatchesAre(scene, w);
    w.gravity = scene.gravity;
    w.globalDamping = scene.globalDamping;
    placeInPeriodicCell(scene, w);
    return w;
}

} // namespace lsdem
