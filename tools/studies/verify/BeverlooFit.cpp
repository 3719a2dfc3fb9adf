#include "studies/verify/BeverlooFit.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lsdem::verify {

namespace {

/// Student's t at 97.5 % (a two-sided 95 % interval) for @a dof degrees of freedom (Abramowitz
/// & Stegun, Table 26.10); NaN for none; the normal's 1.96 beyond 30.
double studentT975(int dof)
{
    static const double t[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262,
                               2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101,
                               2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052,
                               2.048, 2.045, 2.042};
    if (dof < 1) return std::numeric_limits<double>::quiet_NaN();
    return dof <= 30 ? t[dof - 1] : 1.96;
}

} // namespace

LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y)
{
    const size_t n = x.size();
    if (n < 2 || y.size() != n) throw Error("", "fitLine: needs two points or more");
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
    mx /= double(n);
    my /= double(n);
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
        syy += (y[i] - my) * (y[i] - my);
    }
    if (!(sxx > 0.0)) throw Error("", "fitLine: the points share one x");
    LineFit fit;
    fit.slope = sxy / sxx;
    fit.intercept = my - fit.slope * mx;
    double residual = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double r = y[i] - (fit.slope * x[i] + fit.intercept);
        residual += r * r;
    }
    fit.rSquared = syy > 0.0 ? 1.0 - residual / syy : 1.0;
    fit.degreesOfFreedom = static_cast<int>(n) - 2;
    const double variance = fit.degreesOfFreedom > 0 ? residual / fit.degreesOfFreedom
                                                     : std::numeric_limits<double>::quiet_NaN();
    fit.slopeVariance = variance / sxx;
    fit.interceptVariance = variance * (1.0 / double(n) + mx * mx / sxx);
    fit.covariance = -mx * variance / sxx;
    return fit;
}

double beverlooFlow(double c, double bulkDensity, double gravity, double diameter,
                    double emptyAnnulus)
{
    return c * bulkDensity * std::sqrt(gravity) * std::pow(diameter - emptyAnnulus, 2.5);
}

BeverlooFit fitBeverloo(const std::vector<Discharge>& flows, double bulkDensity, double gravity,
                        double grainSize)
{
    std::vector<double> d, w;
    for (const Discharge& f : flows) {
        d.push_back(f.diameter);
        w.push_back(std::pow(f.massFlow, 0.4));
    }
    // W^(2/5) = (C·ρ_b·sqrt(g))^(2/5)·(D − k·d): slope s = (C·ρ_b·sqrt(g))^(2/5), root k·d.
    const LineFit line = fitLine(d, w);
    BeverlooFit fit;
    fit.c = std::pow(line.slope, 2.5) / (bulkDensity * std::sqrt(gravity));
    fit.k = -line.intercept / line.slope / grainSize;
    fit.rSquared = line.rSquared;
    const double t = studentT975(line.degreesOfFreedom);
    const double s = line.slope, b = line.intercept;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (std::isnan(t)) {
        fit.cLow95 = fit.cHigh95 = fit.kLow95 = fit.kHigh95 = nan;
        return fit;
    }
    // C = s^(5/2)/(ρ_b·√g) rises with s: the ends of s's interval give C's (a slope below zero
    // is no flow: C = 0).
    const double sHalf = t * std::sqrt(line.slopeVariance);
    auto cOf = [&](double slope) {
        return std::pow(std::max(slope, 0.0), 2.5) / (bulkDensity * std::sqrt(gravity));
    };
    fit.cLow95 = cOf(s - sHalf);
    fit.cHigh95 = cOf(s + sHalf);
    // Fieller: θ = b/s is in the interval where (b − θ·s)² ≤ t²·(Var b − 2θ·Cov + θ²·Var s),
    // a quadratic a·θ² + 2·h·θ + e ≤ 0. With a > 0 (the slope significant) that is the span
    // between its roots; otherwise it is unbounded.
    const double t2 = t * t;
    const double a = s * s - t2 * line.slopeVariance, h = t2 * line.covariance - b * s,
                 e = b * b - t2 * line.interceptVariance;
    if (a > 0.0) {
        // (Real roots: the estimate b/s itself is inside. Rounding may leave −0 for an exact line.)
        const double root = std::sqrt(std::max(h * h - a * e, 0.0));
        // k = −θ/d: the larger θ gives the smaller k.
        fit.kLow95 = -((-h + root) / a) / grainSize;
        fit.kHigh95 = -((-h - root) / a) / grainSize;
    } else {
        fit.kLow95 = -std::numeric_limits<double>::infinity();
        fit.kHigh95 = std::numeric_limits<double>::infinity();
    }
    return fit;
}

double fittedExponent(const std::vector<Discharge>& flows, double emptyAnnulus)
{
    std::vector<double> x, y;
    for (const Discharge& f : flows) {
        x.push_back(std::log(f.diameter - emptyAnnulus));
        y.push_back(std::log(f.massFlow));
    }
    return fitLine(x, y).slope;
}

} // namespace lsdem::verify
