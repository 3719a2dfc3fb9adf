#include "studies/verify/VerifySetup.h"

#include "lsdem/ls/Bake.h"
#include "lsdem/scene/BuildWorld.h"

#include <sstream>

namespace lsdem::verify {

std::shared_ptr<const GrainAsset> Bodies::bake(const std::string& key, const AnalyticShape& shape,
                                               const BakeOptions& options)
{
    const auto found = mCache.find(key);
    if (found != mCache.end()) return found->second;
    std::vector<std::string> warnings;
    auto asset = std::make_shared<const GrainAsset>(bakeAnalytic(shape, options, warnings));
    return mCache.emplace(key, asset).first->second;
}

std::shared_ptr<const GrainAsset> Bodies::sphere(double radius, int nodes, double voxel)
{
    BakeOptions o;
    o.voxelSize = voxel;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = nodes;
    std::ostringstream key;
    key << "sphere " << radius << " " << nodes << " " << voxel;
    return bake(key.str(), AnalyticShape::sphere(radius), o);
}

std::shared_ptr<const GrainAsset> Bodies::box(const Vec3& edges, double spacing, double voxel)
{
    BakeOptions o;
    o.voxelSize = voxel;
    o.nodePlacement = NodePlacement::Spacing;
    o.nodeSpacing = spacing;
    std::ostringstream key;
    key << "box " << edges.transpose() << " " << spacing << " " << voxel;
    return bake(key.str(), AnalyticShape::box(edges.x(), edges.y(), edges.z()), o);
}

std::shared_ptr<const GrainAsset> Bodies::ellipsoid(const Vec3& axes, int nodes, double voxel)
{
    BakeOptions o;
    o.voxelSize = voxel;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = nodes;
    std::ostringstream key;
    key << "ellipsoid " << axes.transpose() << " " << nodes << " " << voxel;
    return bake(key.str(), AnalyticShape::ellipsoid(axes.x(), axes.y(), axes.z()), o);
}

namespace {

double meanNodeArea(const GrainAsset& asset)
{
    return asset.nodes.totalArea() / static_cast<double>(asset.nodes.size());
}

} // namespace

ContactModel lawFor(Formulation f, const Setup& setup, const GrainAsset& asset, double friction,
                    double restitution, double singleNodeStiffness)
{
    ContactModel m;
    m.formulation = f;
    // The suite's tractions k* and ks* in each law's own stiffness (per node area for original);
    // a law with no traction (single node) takes the spring it is given.
    const double area = meanNodeArea(asset);
    const NormalModel& normal = m.normal();
    m.normalStiffness = normal.stiffnessForTraction(setup.knStar, area).value_or(singleNodeStiffness);
    m.shearStiffness = normal.stiffnessForTraction(setup.ksStar, area).value_or(0.0);
    if (!m.normal().perNodeForces() || !(friction > 0.0)) m.shearStiffness = 0.0;
    m.friction = m.shearStiffness > 0.0 ? friction : 0.0;
    m.damping = ViscousDamping(restitution);
    return m;
}

double tractionStiffness(const ContactModel& model, const GrainAsset& asset)
{
    if (!model.normal().stiffnessPerArea() && !model.normal().perNodeForces()) return 0.0;
    return model.normal().patchStiffness(model.normalStiffness, 1.0, meanNodeArea(asset));
}

Scene caseScene(const Setup& setup, const ContactModel& model)
{
    Scene s;
    s.materials.push_back({"body", setup.density});
    s.materials.push_back({"wall", 0.0});
    for (int other : {0, 1}) {
        ContactSpec c;
        c.materialA = 0;
        c.materialB = other;
        c.model = model;
        c.where = "verification case";
        s.contacts.push_back(c);
    }
    return s;
}

int addGrain(Scene& scene, const std::string& assetName, std::shared_ptr<const GrainAsset> asset,
             const Vec3& position, const Vec3& velocity, const Vec3& angularVelocity,
             const Quat& orientation)
{
    int index = -1;
    for (size_t k = 0; k < scene.assets.size(); ++k)
        if (scene.assets[k].name == assetName) index = static_cast<int>(k);
    if (index < 0) {
        AssetSpec a;
        a.name = assetName;
        a.loaded = std::move(asset);
        a.where = "verification case";
        scene.assets.push_back(a);
        index = static_cast<int>(scene.assets.size()) - 1;
    }
    GrainSpec g;
    g.asset = index;
    g.material = 0;
    g.pose.position = position;
    g.pose.orientation = orientation;
    g.velocity = velocity;
    g.angularVelocity = angularVelocity;
    scene.grains.push_back(g);
    return static_cast<int>(scene.grains.size()) - 1;
}

void addWall(Scene& scene, const Vec3& point, const Vec3& normal)
{
    BoundarySpec b;
    b.name = "wall" + std::to_string(scene.boundaries.size());
    b.shape = BoundaryShape::Plane;
    b.material = 1;
    b.point = point;
    b.normal = normal.normalized();
    scene.boundaries.push_back(b);
}

World buildCase(const Scene& scene)
{
    std::vector<std::string> warnings;
    return buildWorld(scene, warnings);
}

} // namespace lsdem::verify
