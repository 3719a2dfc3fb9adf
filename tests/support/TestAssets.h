/// @file TestAssets.h
/// @brief Tiny stand-ins the simulation tests share: a grain asset of six surface nodes (no
///        level set), an analytic shape baked, and a latex membrane's rubber.
#pragma once

#include "lsdem/ls/Bake.h"
#include "lsdem/ls/GrainAsset.h"
#include "lsdem/simulation/Membrane.h"

#include <memory>
#include <string>
#include <vector>

namespace lsdem::test {

/// Six nodes on the axes of a unit ball, each of area @a nodeArea, normals outward: enough
/// for a plane to press on (no level set: nothing that needs one may use it).
inline GrainAsset sixNodeAsset(double nodeArea)
{
    GrainAsset a;
    for (int axis = 0; axis < 3; ++axis)
        for (double s : {1.0, -1.0}) {
            Vec3 p = Vec3::Zero();
            p[axis] = s;
            a.nodes.positions.push_back(p);
            a.nodes.normals.push_back(p);
            a.nodes.areas.push_back(nodeArea);
        }
    a.boundingRadius = 1.0;
    return a;
}

/// Latex as in a triaxial cell: E 1.4 MPa, 0.3 mm thick, ν @a poisson; @a density mass-scaled
/// (a thousand times rubber's by default, as a quasi-static test uses). Units: mm, N, s, tonne.
/// @a shape baked at voxel size @a voxel with about @a nodes surface nodes.
inline std::shared_ptr<const GrainAsset> bakedShape(const AnalyticShape& shape, double voxel,
                                                    int nodes)
{
    BakeOptions o;
    o.voxelSize = voxel;
    o.nodePlacement = NodePlacement::Count;
    o.nodeCount = nodes;
    std::vector<std::string> warnings;
    return std::make_shared<const GrainAsset>(bakeAnalytic(shape, o, warnings));
}

inline MembraneMaterial latexRubber(double poisson = 0.45, double density = 1e-6)
{
    MembraneMaterial r;
    r.youngs = 1.4;
    r.poisson = poisson;
    r.thickness = 0.3;
    r.density = density;
    return r;
}

} // namespace lsdem::test
