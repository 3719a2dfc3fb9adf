#include "studies/Cube27Scene.h"

#include "lsdem/scene/RandomRotation.h"

#include <random>

namespace lsdem {

namespace {

/// The sphere every grain shares: @a sphere when given (baked once for the study), else
/// baked by the scene with run @a run's node count.
void addSphereAsset(Scene& scene, const Cube27Options& o, const Cube27Run& run,
                    std::shared_ptr<const GrainAsset> sphere)
{
    AssetSpec asset;
    asset.name = "sphere";
    if (!sphere) {
        asset.shape = AnalyticShape::sphere(o.radius);
        asset.bake.voxelSize = o.voxel;
        asset.bake.nodePlacement = NodePlacement::Count;
        asset.bake.nodeCount = run.nodes;
    } else {
        asset.loaded = std::move(sphere);
    }
    asset.where = scene.path;
    scene.assets.push_back(asset);
}

/// Run @a run's law between the spheres (material 0) and between a sphere and a wall
/// (material 1).
void addContactLaws(Scene& scene, const Cube27Options& o, const Cube27Run& run)
{
    ContactModel model;
    model.formulation = run.formulation;
    model.testing = o.testing;
    model.normalStiffness = run.stiffness;
    // Friction acts through shear springs, which single-node and volume do not have: their
    // contacts are frictionless, and the scene says so (a scene file with friction there is
    // refused by the reader).
    if (normalModel(run.formulation).perNodeForces() && o.shearRatio > 0) {
        model.shearStiffness = o.shearRatio * run.stiffness;
        model.friction = o.friction;
    }
    for (int other : {0, 1}) {
        ContactSpec c;
        c.materialA = 0;
        c.materialB = other;
        c.model = model;
        c.model.damping = ViscousDamping(o.restitution);
        c.where = scene.path;
        scene.contacts.push_back(c);
    }
}

/// The 3×3×3 stack of touching spheres in the box's corner. The orientation set: one random
/// rotation per grain, the same set for every N and law.
void addSphereStack(Scene& scene, const Cube27Options& o, const Cube27Run& run)
{
    const double r = o.radius;
    std::mt19937_64 rng(o.seed * 7919u + unsigned(run.orientation));
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                GrainSpec g;
                g.name = "sphere_" + std::to_string(i) + std::to_string(j) + std::to_string(k);
                g.asset = 0;
                g.material = 0;
                g.pose.position = Vec3((2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r);
                g.pose.orientation = randomRotation(rng);
                g.where = scene.path;
                scene.grains.push_back(g);
            }
}

/// The six walls of the box of side @a side around the stack; the top one (boundary 1) comes
/// down at the run's speed.
void addBoxWalls(Scene& scene, double side, const Cube27Run& run)
{
    auto wall = [&](const std::string& name, const Vec3& point, const Vec3& normal) {
        BoundarySpec b;
        b.name = name;
        b.shape = BoundaryShape::Plane;
        b.material = 1;
        b.point = point;
        b.normal = normal;
        b.where = scene.path;
        scene.boundaries.push_back(b);
    };
    wall("floor", Vec3(0, 0, 0), Vec3::UnitZ());
    wall("top", Vec3(0, 0, side), -Vec3::UnitZ());
    wall("west", Vec3(0, 0, 0), Vec3::UnitX());
    wall("east", Vec3(side, 0, 0), -Vec3::UnitX());
    wall("south", Vec3(0, 0, 0), Vec3::UnitY());
    wall("north", Vec3(0, side, 0), -Vec3::UnitY());
    scene.boundaries[1].velocity = Vec3(0, 0, -run.speed);
}

} // namespace

Scene makeCube27Scene(const Cube27Options& o, const Cube27Run& run,
                      std::shared_ptr<const GrainAsset> sphere)
{
    Scene scene;
    scene.path = "(lsdem-study cube27)";
    addSphereAsset(scene, o, run, std::move(sphere));
    scene.materials.push_back({"steel", o.density});
    scene.materials.push_back({"wall", 0.0});
    addContactLaws(scene, o, run);
    addSphereStack(scene, o, run);
    addBoxWalls(scene, 6.0 * o.radius, run);

    scene.gravity = Vec3::Zero();
    scene.globalDamping = o.globalDamping;
    scene.timeStep.fixed = run.timeStep;
    scene.end.boundary = 1;
    scene.end.displacement = o.deltaMax;
    scene.end.steps = run.steps;
    return scene;
}

} // namespace lsdem
