#include "lsdem/ls/SphericalHarmonics.h"

#include "lsdem/core/Constants.h"

#include <cmath>

namespace lsdem {

void realSphericalHarmonics(int maxDegree, double theta, double phi, std::vector<double>& values)
{
    const int L = maxDegree;
    values.assign(static_cast<size_t>((L + 1) * (L + 1)), 0.0);
    const double x = std::cos(theta), s = std::sin(theta);
    // p[l][m] = N_lm P_l^m(x) with N_lm = sqrt((2l+1)/(4π) (l-m)!/(l+m)!), column by column:
    // the diagonal from p_00, the first off-diagonal from it, then the three-term recurrence.
    std::vector<double> p(static_cast<size_t>((L + 1) * (L + 1)), 0.0);
    auto at = [&](int l, int m) -> double& { return p[static_cast<size_t>(l * (L + 1) + m)]; };
    at(0, 0) = std::sqrt(1.0 / (4.0 * kPi));
    for (int m = 1; m <= L; ++m)
        at(m, m) = std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * s * at(m - 1, m - 1);
    for (int m = 0; m < L; ++m) at(m + 1, m) = std::sqrt(2.0 * m + 3.0) * x * at(m, m);
    for (int m = 0; m <= L; ++m)
        for (int l = m + 2; l <= L; ++l) {
            const double a = std::sqrt((4.0 * l * l - 1.0) / (double(l) * l - double(m) * m));
            const double b = std::sqrt((double(l - 1) * (l - 1) - double(m) * m) /
                                       (4.0 * double(l - 1) * (l - 1) - 1.0));
            at(l, m) = a * (x * at(l - 1, m) - b * at(l - 2, m));
        }
    const double root2 = std::sqrt(2.0);
    for (int l = 0; l <= L; ++l) {
        auto value = [&](int m) -> double& {
            return values[static_cast<size_t>(harmonicIndex(l, m))];
        };
        value(0) = at(l, 0);
        for (int m = 1; m <= l; ++m) {
            value(m) = root2 * at(l, m) * std::cos(m * phi);
            value(-m) = root2 * at(l, m) * std::sin(m * phi);
        }
    }
}

} // namespace lsdem
