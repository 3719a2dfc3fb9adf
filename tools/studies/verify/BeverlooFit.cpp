#include "studies/verify/BeverlooFit.h"

#include "lsdem/core/Error.h"

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
    // C = s^(5/2)/(ρ_b·√g): dC/ds = 2.5·C/s. k = −b/(s·d): dk/ds = b/(s²·d), dk/db = −1/(s·d).
    const double t = studentT975(line.degreesOfFreedom);
    const double s = line.slope, b = line.intercept;
    fit.cHalfWidth95 = t * 2.5 * fit.c / s * std::sqrt(line.slopeVariance);
    const double ks = b / (s * s * grainSize), kb = -1.0 / (s * grainSize);
    fit.kHalfWidth95 = t * std::sqrt(ks * ks * line.slopeVariance + kb * kb * line.interceptVariance +
                                     2.0 * ks * kb * line.covariance);
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
