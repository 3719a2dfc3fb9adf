#include "studies/verify/FreeRotationReference.h"

#include "lsdem/core/Constants.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace lsdem::verify {

double completeEllipticK(double k)
{
    if (!(k >= 0.0 && k < 1.0)) throw std::invalid_argument("completeEllipticK: k in [0, 1)");
    double a = 1.0, b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 100 && std::abs(a - b) > 1e-16 * a; ++i) {
        const double mean = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = mean;
    }
    return kPi / (2.0 * a);
}

double intermediateAxisFlipTime(const Vec3& moments, const Vec3& omega)
{
    double i1 = moments.x(), i2 = moments.y(), i3 = moments.z();
    if (!(0.0 < i1 && i1 < i2 && i2 < i3))
        throw std::invalid_argument("intermediateAxisFlipTime: moments must ascend strictly");
    const double twiceEnergy = i1 * omega.x() * omega.x() + i2 * omega.y() * omega.y() +
                               i3 * omega.z() * omega.z();
    const double momentum2 = i1 * i1 * omega.x() * omega.x() + i2 * i2 * omega.y() * omega.y() +
                             i3 * i3 * omega.z() * omega.z();
    if (momentum2 == twiceEnergy * i2)
        throw std::invalid_argument("intermediateAxisFlipTime: on the separatrix");
    // Below the separatrix the body circles axis 1 instead of 3: the same formulas with the
    // first and third axes exchanged (their differences then change sign together).
    if (momentum2 < twiceEnergy * i2) std::swap(i1, i3);
    const double rate2 = (i3 - i2) * (momentum2 - twiceEnergy * i1) / (i1 * i2 * i3);
    const double modulus2 =
        (i2 - i1) * (twiceEnergy * i3 - momentum2) / ((i3 - i2) * (momentum2 - twiceEnergy * i1));
    return 2.0 * completeEllipticK(std::sqrt(modulus2)) / std::sqrt(rate2);
}

} // namespace lsdem::verify
