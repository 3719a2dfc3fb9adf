#include "lsdem/ls/LevelSetGrid.h"

#include <mutex>

namespace lsdem {

void initializeOpenVdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr makeGridTransform(double voxelSize, const Vec3& origin)
{
    auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
    return xform;
}

} // namespace lsdem
