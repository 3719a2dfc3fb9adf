#include "studies/verify/NormalImpactReference.h"

#include "lsdem/core/Constants.h"
#include "lsdem/ls/GaussLegendre.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace lsdem::verify {

namespace {

/// ∫₀^@a upper f by 48-point Gauss–Legendre.
double integrate(const std::function<double(double)>& f, double upper)
{
    static const auto rule = [] {
        std::pair<std::vector<double>, std::vector<double>> r;
        gaussLegendre(48, r.first, r.second);
        return r;
    }();
    double sum = 0.0;
    for (size_t i = 0; i < rule.first.size(); ++i)
        sum += rule.second[i] * f(0.5 * upper * (rule.first[i] + 1.0));
    return 0.5 * upper * sum;
}

} // namespace

NormalImpact powerLawImpact(double kappa, double exponent, double mass, double speed)
{
    if (!(kappa > 0.0) || !(exponent >= 1.0) || !(mass > 0.0) || !(speed > 0.0))
        throw std::invalid_argument("powerLawImpact: needs kappa, mass, speed > 0, exponent >= 1");
    const double q = 1.0 / (exponent + 1.0);
    NormalImpact r;
    r.maxOverlap = std::pow((exponent + 1.0) * mass * speed * speed / (2.0 * kappa), q);
    r.peakForce = kappa * std::pow(r.maxOverlap, exponent);
    // ∫₀¹ dx/sqrt(1 − x^(p+1)) = B(q, ½)·q = √π·Γ(1 + q)/Γ(½ + q).
    r.contactTime = 2.0 * r.maxOverlap / speed * std::sqrt(kPi) * std::tgamma(1.0 + q) /
                    std::tgamma(0.5 + q);
    return r;
}

NormalImpact piecewiseLawImpact(const std::function<double(double)>& force,
                                const std::function<double(double)>& energy, double onset,
                                double mass, double speed, double overlapScale)
{
    const double kinetic = 0.5 * mass * speed * speed;
    double low = onset, high = onset + overlapScale;
    while (energy(high) < kinetic) {
        high = onset + 2.0 * (high - onset);
        if (high - onset > 1e6 * overlapScale)
            throw std::invalid_argument("piecewiseLawImpact: the law never stops the body");
    }
    for (int i = 0; i < 200 && high - low > 1e-15 * high; ++i) {
        const double mid = 0.5 * (low + high);
        (energy(mid) < kinetic ? low : high) = mid;
    }
    NormalImpact r;
    r.maxOverlap = 0.5 * (low + high);
    r.peakForce = force(r.maxOverlap);
    // The contact lasts from the onset to δmax and back: with δ = δmax − (δmax − onset)·s²: dδ = 2·(δmax − onset)·s ds, and v² − 2U(δ)/m vanishes like
    // s² at s = 0, so the integrand stays finite.
    const double span = r.maxOverlap - onset;
    const auto integrand = [&](double s) {
        if (s <= 0.0) return 2.0 * span / std::sqrt(2.0 * force(r.maxOverlap) * span / mass);
        const double overlap = r.maxOverlap - span * s * s;
        const double rest = speed * speed - 2.0 * energy(overlap) / mass;
        return 2.0 * span * s / std::sqrt(std::max(rest, 1e-300));
    };
    constexpr int kPanels = 256;
    double inside = 0.0;
    for (int k = 0; k < kPanels; ++k)
        inside += integrate([&](double u) { return integrand((k + u * kPanels) / kPanels); },
                            1.0 / kPanels);
    r.contactTime = 2.0 * inside;
    return r;
}

NormalImpact forceLawImpact(const std::function<double(double)>& force, double mass,
                            double speed, double overlapScale)
{
    return piecewiseLawImpact(
        force, [&](double overlap) { return integrate(force, overlap); }, 0.0, mass, speed,
        overlapScale);
}

std::vector<std::vector<double>> impactCourse(const std::function<double(double)>& force,
                                              double mass, double speed, double step)
{
    std::vector<std::vector<double>> rows;
    const auto accel = [&](double d) { return d > 0.0 ? -force(d) / mass : 0.0; };
    double t = 0.0, d = 0.0, v = speed;
    rows.push_back({t, d, 0.0});
    for (long k = 0; k < 10000000; ++k) {
        const double k1d = v, k1v = accel(d);
        const double k2d = v + 0.5 * step * k1v, k2v = accel(d + 0.5 * step * k1d);
        const double k3d = v + 0.5 * step * k2v, k3v = accel(d + 0.5 * step * k2d);
        const double k4d = v + step * k3v, k4v = accel(d + step * k3d);
        d += step / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        v += step / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        t += step;
        if (d <= 0.0) break;
        rows.push_back({t, d, force(d)});
    }
    return rows;
}

} // namespace lsdem::verify
