#include "lsdem/contact/SphereContactReference.h"

#include "lsdem/core/Constants.h"
#include "lsdem/ls/GaussLegendre.h"

#include <cmath>
#include <utility>
#include <vector>

namespace lsdem {

namespace {

/// ∫_cap d (n·e)^p dA with p = 1 (@a alongAxis) or 0, times @a stiffness.
double capIntegral(double radius, double overlap, double stiffness, bool alongAxis)
{
    if (overlap <= 0.0) return 0.0;
    const double r = radius, h = 2.0 * radius - overlap;
    const double lo = h / (2.0 * r), hi = 1.0;
    // The rule is worked out once (Newton's method on the recurrence: most of a call's time).
    static const auto rule = [] {
        std::pair<std::vector<double>, std::vector<double>> nodesAndWeights;
        gaussLegendre(64, nodesAndWeights.first, nodesAndWeights.second);
        return nodesAndWeights;
    }();
    const std::vector<double>& x = rule.first;
    const std::vector<double>& w = rule.second;
    double sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double u = 0.5 * (hi - lo) * x[i] + 0.5 * (hi + lo);
        const double rho = std::sqrt(r * r + h * h - 2.0 * r * h * u);
        sum += w[i] * (r - rho) * (alongAxis ? (h - r * u) / rho : 1.0);
    }
    return stiffness * 2.0 * kPi * r * r * 0.5 * (hi - lo) * sum;
}

} // namespace

double exactSphereContactForce(double radius, double overlap, double knStar)
{
    return capIntegral(radius, overlap, knStar, true);
}

double exactSphereVolumeForce(double radius, double overlap, double kv)
{
    return capIntegral(radius, overlap, kv, false);
}

double leadingOrderSphereContactForce(double radius, double overlap, double knStar)
{
    return overlap <= 0.0 ? 0.0 : 0.5 * kPi * knStar * radius * overlap * overlap;
}

} // namespace lsdem
