#include "lsdem/scene/EntryRules.h"

#include "lsdem/core/NumberRange.h"
#include "lsdem/core/NumberText.h"

#include <cmath>

namespace lsdem {

const char* const kDensityFix =
    "give a density in mass/length³ (0 for a material only boundaries use)";

std::optional<std::string> densityProblem(double density)
{
    return outOfRange(NumberRange::NonNegative, density);
}

const char* const kOrientationFix =
    "give a unit quaternion [w, x, y, z], asset frame to world (e.g. [1, 0, 0, 0])";

std::optional<std::string> orientationProblem(const Quat& q, double tolerance)
{
    const double norm = q.norm();
    if (!(norm > 1e-12)) return "is not a rotation (zero quaternion)";
    if (!(std::abs(norm - 1.0) <= tolerance))
        return "is not a unit quaternion (norm " + numberText(norm) + ")";
    return std::nullopt;
}

} // namespace lsdem
