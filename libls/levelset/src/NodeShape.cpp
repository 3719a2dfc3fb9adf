#include "lsdem/ls/NodeShape.h"

#include "lsdem/ls/GrainAsset.h"
#include "lsdem/ls/LevelSetSampler.h"

#include "lsdem/core/Constants.h"

#include <algorithm>
#include <cmath>

namespace lsdem {

namespace {

/// A unit vector ⊥ @a m, from the axis least aligned with it (so never degenerate).
Vec3 anyTangent(const Vec3& m)
{
    Eigen::Index axis = 0;
    m.cwiseAbs().minCoeff(&axis);
    const Vec3 t = m.cross(Vec3::Unit(axis));
    return t.normalized();
}

} // namespace

std::vector<NodeShape> nodeShapesOf(const GrainAsset& asset)
{
    std::vector<NodeShape> shapes(asset.nodes.size());
    LevelSetSampler sampler(*asset.levelSet);
    const double h = asset.voxelSize;
    for (size_t i = 0; i < shapes.size(); ++i) {
        const Vec3& x = asset.nodes.positions[i];
        NodeShape& s = shapes[i];
        const Vec3 gradient = sampler.sample(x).gradient;
        const double length = gradient.norm();
        if (!(length > 0.0)) {
            s.normal = x.norm() > 0.0 ? Vec3(x.normalized()) : Vec3::UnitZ();
            s.tangent = anyTangent(s.normal);
            continue;  // flat: no curvature known
        }
        s.normal = gradient / length;
        s.tangent = anyTangent(s.normal);
        const Vec3 t2 = s.secondTangent();
        // ∇φ's change along each tangent: the Hessian's columns H·t (central differences).
        auto change = [&](const Vec3& t) {
            return Vec3((sampler.sample(x + h * t).gradient - sampler.sample(x - h * t).gradient) /
                        (2.0 * h));
        };
        const Vec3 along1 = change(s.tangent), along2 = change(t2);
        s.k11 = s.tangent.dot(along1);
        s.k22 = t2.dot(along2);
        s.k12 = 0.5 * (t2.dot(along1) + s.tangent.dot(along2));
    }
    return shapes;
}

double patchReachOf(const GrainAsset& asset, const std::vector<NodeShape>& shapes)
{
    double reach = 0.0;
    for (size_t i = 0; i < shapes.size(); ++i) {
        const NodeShape& s = shapes[i];
        const double radius = std::sqrt(asset.nodes.areas[i] / kPi);
        const double mean = 0.5 * (s.k11 + s.k22), half = 0.5 * (s.k11 - s.k22);
        const double lowest = mean - std::sqrt(half * half + s.k12 * s.k12);
        reach = std::max(reach, radius + 0.5 * radius * radius * std::max(0.0, -lowest));
    }
    return reach;
}

GrainAsset withNodeShapes(const GrainAsset& asset)
{
    GrainAsset out = asset;
    out.nodeShapes = nodeShapesOf(asset);
    out.patchReach = patchReachOf(asset, out.nodeShapes);
    return out;
}

} // namespace lsdem
