#include "lsdem/contact/SphereContactReference.h"

#include "lsdem/ls/Constants.h"
#include "lsdem/ls/GaussLegendre.h"

#include <cmath>
#include <vector>

namespace lsdem {

namespace {

} // namespace

double exactSphereContactForce(double radius, double overlap, double knStar)
{
    if (overlap <= 0.0) return 0.0;
    const double r = radius, h = 2.0 * radius - overlap;
    const double lo = h / (2.0 * r), hi = 1.0;
    std::vector<double> x, w;
    gaussLegendre(64, x, w);
    double sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double u = 0.5 * (hi - lo) * x[i] + 0.5 * (hi + lo);
        const double rho = std::sqrt(r * r + h * h - 2.0 * r * h * u);
        sum += w[i] * (r - rho) * (h - r * u) / rho;
    }
    return knStar * 2.0 * kPi * r * r * 0.5 * (hi - lo) * sum;
}

double leadingOrderSphereContactForce(double radius, double overlap, double knStar)
{
    return overlap <= 0.0 ? 0.0 : 0.5 * kPi * knStar * radius * overlap * overlap;
}

} // namespace lsdem
