/// @file VerifySetup.h
/// @brief The bodies, materials and contact laws of the verification suite, and the scenes
///        its cases run: lsdem's standard sphere (radius 5 mm, steel, 4000 nodes at voxel
///        0.1 mm) and the paper's law (kn* = 1e3 N/mm³, that is 1 GPa/mm; ks* = kn*/2), with
///        the kinematics, friction and restitution of the published tests. Units: mm, t, s, N.
#pragma once

#include "lsdem/scene/Scene.h"
#include "lsdem/simulation/World.h"

#include <map>
#include <memory>
#include <string>

namespace lsdem::verify {

struct Setup
{
    int sphereNodes = 4000;     ///< about; the bake places nearly as many
    double sphereVoxel = 0.1;   ///< mm
    double radius = 5.0;        ///< mm
    double density = 7.85e-9;   ///< t/mm³ (steel)
    double knStar = 1e3;        ///< N/mm³
    double ksStar = 0.5e3;      ///< N/mm³
    double gravity = 9810.0;    ///< mm/s²
};

/// Bakes each body once, for every case that uses it.
class Bodies
{
public:
    explicit Bodies(const Setup& setup) : mSetup(setup) {}
    const Setup& setup() const { return mSetup; }

    std::shared_ptr<const GrainAsset> sphere(double radius, int nodes, double voxel);
    /// The setup's sphere.
    std::shared_ptr<const GrainAsset> sphere()
    {
        return sphere(mSetup.radius, mSetup.sphereNodes, mSetup.sphereVoxel);
    }
    /// A box of full edges @a edges, nodes at @a spacing.
    std::shared_ptr<const GrainAsset> box(const Vec3& edges, double spacing, double voxel);
    /// An ellipsoid of semi-axes @a axes, about @a nodes nodes.
    std::shared_ptr<const GrainAsset> ellipsoid(const Vec3& axes, int nodes, double voxel);

private:
    std::shared_ptr<const GrainAsset> bake(const std::string& key, const AnalyticShape& shape,
                                           const BakeOptions& options);
    Setup mSetup;
    std::map<std::string, std::shared_ptr<const GrainAsset>> mCache;
};

/// The law of formulation @a f that stands for the setup's adapted law on @a asset: the same
/// traction stiffness in the continuum limit (original: kn = kn*·Ā and ks = ks*·Ā with Ā the
/// mean node area; volume: kv = kn*; single-node: @a singleNodeStiffness, a spring with no
/// traction to match), shear springs with friction @a friction where the law has per-node
/// forces, and restitution @a restitution.
ContactModel lawFor(Formulation f, const Setup& setup, const GrainAsset& asset, double friction,
                    double restitution, double singleNodeStiffness = 0.0);

/// The traction stiffness (force/length³) that @a model's nodes add up to on @a asset in the
/// continuum limit (NormalModel::patchStiffness of a unit area): kn* for adapted, kn/Ā for
/// original, kv for volume. 0 for the single-node law, which has none.
double tractionStiffness(const ContactModel& model, const GrainAsset& asset);

/// A case's scene: materials "body" (the setup's density) and "wall", @a model between every
/// pair of them.
Scene caseScene(const Setup& setup, const ContactModel& model);
/// A free grain of @a asset (added to the scene's assets once, by @a assetName). Returns its
/// index.
int addGrain(Scene& scene, const std::string& assetName, std::shared_ptr<const GrainAsset> asset,
             const Vec3& position, const Vec3& velocity = Vec3::Zero(),
             const Vec3& angularVelocity = Vec3::Zero(),
             const Quat& orientation = Quat::Identity());
/// An unbounded wall through @a point with normal @a normal.
void addWall(Scene& scene, const Vec3& point = Vec3::Zero(), const Vec3& normal = Vec3::UnitZ());
/// The world of @a scene (assets already in memory: nothing is read).
World buildCase(const Scene& scene);

} // namespace lsdem::verify
