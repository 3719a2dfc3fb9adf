#include "lsdem/contact/SphereContactReference.h"

#include <cmath>

namespace lsdem {

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

double exactSphereContactForce(double radius, double overlap, double knStar)
{
    if (overlap <= 0.0) return 0.0;
    const double r = radius, h = 2.0 * radius - overlap;
    const double lo = h / (2.0 * r), hi = 1.0;
    // Gauss–Legendre nodes on [-1, 1] by Newton on the Legendre recurrence.
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = 0.0;
            for (int j = 1; j <= n; ++j) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            const double dz = p0 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        const double w = 2.0 / ((1.0 - z * z) * dp * dp);
        const double u = 0.5 * (hi - lo) * z + 0.5 * (hi + lo);
        const double rho = std::sqrt(r * r + h * h - 2.0 * r * h * u);
        sum += w * (r - rho) * (h - r * u) / rho;
    }
    return knStar * 2.0 * kPi * r * r * 0.5 * (hi - lo) * sum;
}

double leadingOrderSphereContactForce(double radius, double overlap, double knStar)
{
    return overlap <= 0.0 ? 0.0 : 0.5 * kPi * knStar * radius * overlap * overlap;
}

} // namespace lsdem
