#include "studies/Cube27ClosedForm.h"

#include "lsdem/core/Constants.h"

#include <cmath>

namespace lsdem {

double cube27ClosedForm(double radius, double delta, double knStar)
{
    if (delta <= 0.0) return 0.0;
    return 9.0 * kPi * knStar * radius * delta * delta / (kCube27Column * kCube27Column);
}

double cube27ExactForce(double radius, double delta, double knStar, Formulation law)
{
    if (delta <= 0.0) return 0.0;
    // The force is linear in k at fixed geometry: solve with k = 1 and scale. Both unknowns
    // solve equations that are nearly linear (sqrt of the sphere force in the overlap, the
    // column travel in d_w), so secant iterations from the parabolic solution converge in a
    // few steps.
    auto secant = [](const auto& f, double x0, double x1) {
        double f0 = f(x0), f1 = f(x1);
        for (int i = 0; i < 60 && f1 != f0; ++i) {
            const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
            x0 = x1;
            f0 = f1;
            x1 = x2;
            f1 = f(x1);
            if (std::abs(x1 - x0) <= 1e-14 * std::abs(x1)) break;
        }
        return x1;
    };
    const NormalModel& model = normalModel(law);
    auto sphereForce = [&](double r, double overlap, double k) {
        return model.continuumSphereForce(r, overlap, k);
    };
    auto travel = [&](double dWall) {
        const double force = kPi * radius * dWall * dWall;  // sphere–plane, exact
        const double dSphere = secant(
            [&](double d) { return std::sqrt(sphereForce(radius, d, 1.0)) - std::sqrt(force); },
            std::sqrt(2.0) * dWall, 1.01 * std::sqrt(2.0) * dWall);
        return 2.0 * dWall + 2.0 * dSphere;
    };
    const double dWall =
        secant([&](double d) { return travel(d) - delta; }, delta / kCube27Column, 0.99 * delta / kCube27Column);
    return 9.0 * kPi * knStar * radius * dWall * dWall;
}

} // namespace lsdem
