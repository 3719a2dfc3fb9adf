#include "lsdem/contact/TangentialModel.h"

namespace lsdem {

Vec3 updateShearForce(const Vec3& stored, const Vec3& normal, const Vec3& slip,
                      double stiffness, double limit)
{
    // Turn the stored force onto the new tangent plane without changing its size: a turning
    // normal must neither create nor destroy shear.
    Vec3 shear = stored - stored.dot(normal) * normal;
    const double before = stored.norm(), after = shear.norm();
    if (after > 0.0) shear *= before / after;
    const Vec3 tangentialSlip = slip - slip.dot(normal) * normal;
    shear -= stiffness * tangentialSlip;
    const double size = shear.norm();
    if (size > limit) shear *= (limit > 0.0 ? limit / size : 0.0);  // sliding: Coulomb cap
    return shear;
}

} // namespace lsdem
