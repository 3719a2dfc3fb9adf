#include "lsdem/ls/MeshLevelSet.h"

#include <openvdb/tools/MeshToVolume.h>

#include <cmath>
#include <limits>
#include <vector>

namespace lsdem {

std::shared_ptr<LevelSetGrid> meshLevelSet(const TriangleMesh& mesh, double voxelSize,
                                           int exteriorBandVoxels)
{
    initializeOpenVdb();
    const auto bounds = meshBounds(mesh);
    const double vox = voxelSize;
    const double pad = (exteriorBandVoxels + 2) * vox;
    Vec3 origin;
    for (int k = 0; k < 3; ++k) origin[k] = vox * std::floor((bounds[0][k] - pad) / vox);
    const auto xform = makeGridTransform(vox, origin);
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    for (const Vec3& v : mesh.vertices) points.emplace_back(float(v.x()), float(v.y()), float(v.z()));
    for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
    auto grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
        *xform, points, triangles, {}, float(exteriorBandVoxels),
        std::numeric_limits<float>::max());
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    auto levelSet = std::make_shared<LevelSetGrid>();
    levelSet->grid = grid;
    levelSet->origin = origin;
    levelSet->voxelSize = vox;
    return levelSet;
}

} // namespace lsdem
