#include "studies/verify/BeverlooFit.h"

#include "lsdem/core/Error.h"

#include <cmath>

namespace lsdem::verify {

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
    return fit;
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
