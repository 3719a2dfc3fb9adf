#include "lsdem/contact/DampingModel.h"

#include "lsdem/ls/Constants.h"

#include <cmath>

namespace lsdem {

ViscousDamping ViscousDamping::fromRestitution(double restitution)
{
    const double logE = std::log(restitution);
    return {-logE / std::sqrt(kPi * kPi + logE * logE)};
}

double ViscousDamping::dashpotPerStiffness(double effectiveMass, double totalStiffness) const
{
    if (!(ratio > 0.0) || !(totalStiffness > 0.0)) return 0.0;
    return 2.0 * ratio * std::sqrt(effectiveMass / totalStiffness);
}

double dampingRatioFromRestitution(double restitution)
{
    return ViscousDamping::fromRestitution(restitution).ratio;
}

} // namespace lsdem
